// tinygltf and stb_image compiled from their headers into the fuzzer, so that the sanitizers and
// libFuzzer's coverage see inside them (clppm itself links Debian's prebuilt libtinygltf and
// libstb, built from these same headers). Only tests/fuzz/build.sh compiles this file.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>

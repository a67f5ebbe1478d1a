#!/bin/sh
# Builds the glTF loader fuzzer: tests/fuzz/build.sh [build_dir]   (default: build-fuzz in the
# repository root, ignored by git). Needs clang++ with libFuzzer (Debian: clang libclang-rt-14-dev)
# and the libraries clppm builds with (tinygltf, nlohmann-json, glm, stb headers).
#
# The loader (src/scene/gltf/*.cpp, src/scene/light_power.cpp, src/util/embedded_files.cpp and the
# embedded default scene), tinygltf
# and stb_image are all compiled with -fsanitize=fuzzer,address,undefined; nothing links the
# prebuilt libtinygltf, so every line that touches the input is instrumented. To replay files
# under the sanitizers without fuzzing: build-fuzz/gltf_fuzz FILE...
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-$root/build-fuzz}
CXX=${CXX:-clang++}
mkdir -p "$out/obj"

# The embedded default scene, as the main build generates it (load_default_scene needs it).
cmake -DOUT="$out/obj/embedded.tmp.cpp" -DKERNELS= -DSCENES="$root/scenes/cornell_box.gltf" \
      -P "$root/cmake/embed_files.cmake"
cmake -E copy_if_different "$out/obj/embedded.tmp.cpp" "$out/obj/embedded_files_generated.cpp"

san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
flags="-std=c++17 -O1 -g $san -I$root/src -I$root/kernels -I/usr/include/stb
       -DCL_TARGET_OPENCL_VERSION=120 -DCLPPM_TEST_DATA=\"$root/tests/data\""
objs=""
compile() { # source object [extra flags]
    src=$1; obj=$2; shift 2
    if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ] || [ "$0" -nt "$obj" ]; then
        echo "compiling $(basename "$src")"
        $CXX $flags "$@" -c "$src" -o "$obj"
    fi
    objs="$objs $obj"
}
cov=-fsanitize=fuzzer-no-link
for src in "$root"/src/scene/gltf/*.cpp "$root/src/scene/light_power.cpp"; do
    compile "$src" "$out/obj/$(basename "$src" .cpp).o" $cov
done
compile "$root/src/util/embedded_files.cpp" "$out/obj/embedded_files.o" $cov
compile "$out/obj/embedded_files_generated.cpp" "$out/obj/embedded_files_generated.o" $cov
compile "$here/tinygltf_impl.cpp" "$out/obj/tinygltf_impl.o" $cov -w
compile "$here/gltf_fuzz.cpp" "$out/obj/gltf_fuzz.o" $cov

echo "linking $out/gltf_fuzz"
$CXX $flags -fsanitize=fuzzer $objs -o "$out/gltf_fuzz"
echo "built $out/gltf_fuzz"

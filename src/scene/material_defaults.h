// glTF 2.0's default material (Sec. 5.19, the material of a primitive that names none): every factor
// at the specification's default, every texture absent (-1). The loader gives it to primitives
// without a material; scenes built in code start from it, so that a texture slot added to
// dev::Material is absent everywhere once it is absent here.
#pragma once
#include "shared_types.h"

namespace clppm {

dev::Material default_material();

} // namespace clppm

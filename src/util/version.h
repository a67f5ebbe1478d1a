#pragma once

namespace clppm {
constexpr const char* kVersion = "clppm 0.1.0";
}

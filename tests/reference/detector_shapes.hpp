// SPDX-License-Identifier: MIT
#pragma once
// The four detector types as GoogleTest type parameters, named float2d ... double3d.

#include <gtest/gtest.h>

#include <string>
#include <type_traits>

namespace smb::test {

template <typename Real, int Dim>
struct Shape {
    using real_type = Real;
    static constexpr int dimension = Dim;
};
using Shapes = ::testing::Types<Shape<float, 2>, Shape<double, 2>, Shape<float, 3>, Shape<double, 3>>;

class ShapeNames {
public:
    template <typename T>
    static std::string GetName(int) {
        return std::string(std::is_same_v<typename T::real_type, float> ? "float" : "double") +
               std::to_string(T::dimension) + "d";
    }
};

}  // namespace smb::test

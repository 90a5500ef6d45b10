// SPDX-License-Identifier: MIT
#pragma once
// The box types the library is built for: each public class template is instantiated for these
// four in its own .cpp (SMB_FOR_EACH_BOX_TYPE(X) expands to X(float, 2) ... X(double, 3)).

#define SMB_FOR_EACH_BOX_TYPE(X) \
    X(float, 2)                  \
    X(double, 2)                 \
    X(float, 3)                  \
    X(double, 3)

// SPDX-License-Identifier: MIT
// The unit that builds the tests' precompiled header (tests/CMakeLists.txt: smb_test_headers).

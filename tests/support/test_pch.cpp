// The executable that builds the test executables' shared precompiled header (tests/CMakeLists.txt, sward_test_pch);
// it does nothing itself.
int main() { return 0; }

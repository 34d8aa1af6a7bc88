// The translation unit that builds the tests' precompiled header (tests/CMakeLists.txt: gusuku_test_precompiled);
// it holds no code of its own.

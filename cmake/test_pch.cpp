// The unit that builds the tests' shared precompiled header (cmake/build_speed.cmake).

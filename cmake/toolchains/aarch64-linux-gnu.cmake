# Cross-compiles for 64-bit ARM Linux (AArch64) with Debian 12's cross toolchain (g++-aarch64-linux-gnu) and its
# multiarch arm64 packages (libvulkan-dev:arm64), for the runtime-only build (-DGUSUKU_RUNTIME_ONLY=ON,
# scripts/cross-build-aarch64.sh). It takes the route the Android NDK's build/cmake/android.toolchain.cmake takes;
# each setting names the NDK's counterpart (docs/platforms.md gives the NDK command line).
#   cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake -DGUSUKU_RUNTIME_ONLY=ON

# The target system. NDK: CMAKE_SYSTEM_NAME Android, with CMAKE_SYSTEM_VERSION the API level from ANDROID_PLATFORM
# (android-24).
set(CMAKE_SYSTEM_NAME Linux)
# The target processor. NDK: ANDROID_ABI arm64-v8a, which it turns into CMAKE_ANDROID_ARCH_ABI and
# CMAKE_SYSTEM_PROCESSOR aarch64.
set(CMAKE_SYSTEM_PROCESSOR aarch64)

# The compilers. NDK: its own clang and clang++ (toolchains/llvm/prebuilt/<host>/bin), given
# --target=aarch64-none-linux-android<API> through CMAKE_<LANG>_COMPILER_TARGET; its C++ library is libc++
# (ANDROID_STL c++_shared or c++_static) where this one's is libstdc++.
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# Where the target's headers and libraries are. NDK: CMAKE_SYSROOT, its toolchains/llvm/prebuilt/<host>/sysroot
# (which holds libvulkan.so for each API level), also put first in CMAKE_FIND_ROOT_PATH. Debian has no sysroot:
# the cross C library is in /usr/aarch64-linux-gnu and the arm64 packages in the multiarch folders
# (/usr/lib/aarch64-linux-gnu), with the architecture-independent headers (vulkan/, glm/) in /usr/include.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu /)

# Programs run on the build machine (glslangValidator compiles the shaders to SPIR-V there); libraries, headers
# and packages are the target's. NDK: the same four CMAKE_FIND_ROOT_PATH_MODE_* settings.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

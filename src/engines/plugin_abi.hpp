#pragma once
// The contract between libstructmd and a plugin library, which exchange C++ objects (registries,
// std::function factories) and so must agree on more than the C ABI: the plugin ABI version (raised
// whenever a type a plugin fills or an entry point changes) and a build fingerprint (the library
// version, the compiler and its C++ library ABI, and whether the library has its CUDA backend). The
// loader (plugin_library.cpp) compares both before it calls anything else of a plugin.
#include <string>  // defines _GLIBCXX_USE_CXX11_ABI

// A plugin built with another value (here by -DSTRUCTMD_PLUGIN_ABI_VERSION=...) is refused.
#ifndef STRUCTMD_PLUGIN_ABI_VERSION
#define STRUCTMD_PLUGIN_ABI_VERSION 10
#endif

#define STRUCTMD_PLUGIN_STR2(x) #x
#define STRUCTMD_PLUGIN_STR(x) STRUCTMD_PLUGIN_STR2(x)

#if defined(__clang__)
#define STRUCTMD_PLUGIN_COMPILER "clang " STRUCTMD_PLUGIN_STR(__clang_major__) "." STRUCTMD_PLUGIN_STR(__clang_minor__)
#elif defined(__GNUC__)
#define STRUCTMD_PLUGIN_COMPILER "gcc " STRUCTMD_PLUGIN_STR(__GNUC__) "." STRUCTMD_PLUGIN_STR(__GNUC_MINOR__)
#else
#define STRUCTMD_PLUGIN_COMPILER "unknown compiler"
#endif

#if defined(_GLIBCXX_USE_CXX11_ABI)
#define STRUCTMD_PLUGIN_STDLIB "libstdc++ abi " STRUCTMD_PLUGIN_STR(_GLIBCXX_USE_CXX11_ABI)
#elif defined(_LIBCPP_VERSION)
#define STRUCTMD_PLUGIN_STDLIB "libc++ " STRUCTMD_PLUGIN_STR(_LIBCPP_VERSION)
#else
#define STRUCTMD_PLUGIN_STDLIB "unknown C++ library"
#endif

#if defined(STRUCTMD_HAVE_CUDA)
#define STRUCTMD_PLUGIN_CUDA "with CUDA"
#else
#define STRUCTMD_PLUGIN_CUDA "without CUDA"
#endif

// "structmd 0.1.0, gcc 13.2, libstdc++ abi 1, with CUDA"
#define STRUCTMD_PLUGIN_BUILD                                                                     \
    "structmd " STRUCTMD_VERSION_STRING ", " STRUCTMD_PLUGIN_COMPILER ", " STRUCTMD_PLUGIN_STDLIB \
    ", " STRUCTMD_PLUGIN_CUDA

// The entry points a plugin exports (STRUCTMD_PLUGIN in plugin.hpp defines them):
//   int structmd_plugin_abi_version(void);           STRUCTMD_PLUGIN_ABI_VERSION of the plugin
//   const char* structmd_plugin_build(void);         STRUCTMD_PLUGIN_BUILD of the plugin
//   int structmd_plugin_register(structmd::ComponentSet* set, char* message, size_t size);
//       adds the plugin's components to `set`; returns 0, or a status with the reason in `message`
namespace structmd {
struct ComponentSet;
using PluginAbiVersionFn = int (*)();
using PluginBuildFn = const char* (*)();
using PluginRegisterFn = int (*)(ComponentSet*, char*, size_t);
}  // namespace structmd

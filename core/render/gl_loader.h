#pragma once

#include <functional>

namespace handlab::render {

// Resolves an OpenGL entry point by name ("glClear") in the current context.
using GlProc = void (*)();
using GlLoader = std::function<GlProc(const char* name)>;

}  // namespace handlab::render

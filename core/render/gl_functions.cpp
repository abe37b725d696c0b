#include "core/render/gl_functions.h"

#include <stdexcept>
#include <string>

namespace handlab::render {

GlFunctions::GlFunctions(const GlLoader& loader) {
#define HANDLAB_GL_LOAD(type, name)                  \
  name = reinterpret_cast<type>(loader("gl" #name)); \
  if (name == nullptr) throw std::runtime_error("OpenGL entry point gl" #name " not found");
  HANDLAB_GL_FUNCTIONS(HANDLAB_GL_LOAD)
#undef HANDLAB_GL_LOAD
}

}  // namespace handlab::render

#include "core/render/renderer.h"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/render/gl_functions.h"

namespace handlab::render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;
uniform vec4 u_clip_plane;  // keeps dot(plane, world) >= 0; (0, 0, 0, 1) keeps everything
out vec3 v_world;
out vec3 v_normal;
out vec2 v_local;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_local = a_position.xy;
  v_normal = u_normal_matrix * a_normal;
  gl_ClipDistance[0] = dot(u_clip_plane, world);
  gl_Position = u_view_projection * world;
}
)";

// Blinn-Phong with a key light, a fill light and ambient; the floor gets a 5 cm checker so
// orbiting reads as motion. One program per shading style (SHADING is defined before the
// source), so that no pixel runs another style's code: a software renderer (llvmpipe) runs
// both sides of a branch, even on a uniform.
constexpr const char* kFragmentShader = R"(
in vec3 v_world;
in vec3 v_normal;
in vec2 v_local;
uniform vec4 u_color;
uniform vec3 u_eye;
uniform sampler2D u_picture;
out vec4 frag_color;
void main() {
#if SHADING == 2
  frag_color = u_color;
#elif SHADING == 3
  frag_color = vec4(texture(u_picture, vec2(v_local.x + 0.5, 0.5 - v_local.y)).rgb, u_color.a);
#else
  vec3 base = u_color.rgb;
#if SHADING == 1
  vec2 cell = floor(v_world.xz / 0.05);
  float checker = mod(cell.x + cell.y, 2.0);
  base *= mix(0.88, 1.0, checker);
#endif
  vec3 n = normalize(v_normal);
  vec3 view = normalize(u_eye - v_world);
  if (dot(n, view) < 0.0) n = -n;
  vec3 key = normalize(vec3(0.35, 1.0, 0.55));
  vec3 fill = normalize(vec3(-0.6, 0.4, -0.3));
  float diffuse = 0.75 * max(dot(n, key), 0.0) + 0.2 * max(dot(n, fill), 0.0);
  // x^48 as x^32 x^16: a software renderer's pow is an exp2 of a log2, many times dearer.
  float h = max(dot(n, normalize(key + view)), 0.0);
  float h2 = h * h, h4 = h2 * h2, h8 = h4 * h4, h16 = h8 * h8;
  float specular = h16 * h16 * h16 * 0.18;
  vec3 color = base * (0.28 + diffuse) + vec3(specular);
  frag_color = vec4(min(color, vec3(1.0)), u_color.a);
#endif
}
)";

GLuint compile(const GlFunctions& gl, GLenum type, const char* prefix, const char* source) {
  const GLuint shader = gl.CreateShader(type);
  const char* parts[] = {prefix, source};
  gl.ShaderSource(shader, 2, parts, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    throw std::runtime_error(std::string("shader compilation failed: ") + log);
  }
  return shader;
}

struct GpuMesh {
  std::weak_ptr<const RenderMesh> source;
  GLuint vao = 0;
  GLuint buffers[3] = {0, 0, 0};  // positions, normals, indices
  GLsizei index_count = 0;
};

}  // namespace

struct Renderer::Impl {
  struct Program {
    GLuint id = 0;
    GLint u_model = -1, u_view_projection = -1, u_normal_matrix = -1, u_color = -1, u_eye = -1,
          u_clip_plane = -1;
  };

  // What the ground's picture was drawn from: it is drawn again when any of it changes.
  struct GroundKey {
    int width = 0, height = 0;
    Eigen::Matrix4f view_projection = Eigen::Matrix4f::Zero();
    Eigen::Vector3f eye = Eigen::Vector3f::Zero(), background = Eigen::Vector3f::Zero();
    std::vector<DrawItem> items;  // holding the meshes keeps their addresses from reuse

    bool operator==(const GroundKey& other) const {
      if (width != other.width || height != other.height ||
          view_projection != other.view_projection || eye != other.eye ||
          background != other.background || items.size() != other.items.size())
        return false;
      for (std::size_t i = 0; i < items.size(); ++i) {
        const DrawItem &a = items[i], &b = other.items[i];
        if (a.mesh != b.mesh || a.dynamic || a.model != b.model || a.color != b.color ||
            a.shading != b.shading || a.picture != b.picture)
          return false;
      }
      return true;
    }
  };

  // The ground's picture, in a framebuffer of its own.
  struct GroundCache {
    GLuint framebuffer = 0, color = 0, depth = 0;
    int width = 0, height = 0;
    std::optional<GroundKey> drawn;
  };

  GlFunctions gl;
  static constexpr int kShadings = 4;
  Program programs[kShadings];  // by Shading
  // Pictures as textures, by the picture's address (freed when nobody holds the picture).
  struct GpuPicture {
    std::weak_ptr<const Image> source;
    GLuint texture = 0;
  };
  std::map<const Image*, GpuPicture> pictures;
  std::map<const RenderMesh*, GpuMesh> meshes;
  GroundCache ground;

  explicit Impl(const GlLoader& loader) : gl(loader) {
    for (int shading = 0; shading < kShadings; ++shading) programs[shading] = link(shading);
  }

  Program link(int shading) {
    const std::string defines =
        "#version 330 core\n#define SHADING " + std::to_string(shading) + "\n";
    const GLuint vs = compile(gl, GL_VERTEX_SHADER, "", kVertexShader);
    const GLuint fs = compile(gl, GL_FRAGMENT_SHADER, defines.c_str(), kFragmentShader);
    Program program;
    program.id = gl.CreateProgram();
    gl.AttachShader(program.id, vs);
    gl.AttachShader(program.id, fs);
    gl.LinkProgram(program.id);
    gl.DeleteShader(vs);
    gl.DeleteShader(fs);
    GLint ok = 0;
    gl.GetProgramiv(program.id, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[2048] = {};
      gl.GetProgramInfoLog(program.id, sizeof log, nullptr, log);
      gl.DeleteProgram(program.id);
      throw std::runtime_error(std::string("shader link failed: ") + log);
    }
    program.u_model = gl.GetUniformLocation(program.id, "u_model");
    program.u_view_projection = gl.GetUniformLocation(program.id, "u_view_projection");
    program.u_normal_matrix = gl.GetUniformLocation(program.id, "u_normal_matrix");
    program.u_color = gl.GetUniformLocation(program.id, "u_color");
    program.u_eye = gl.GetUniformLocation(program.id, "u_eye");
    program.u_clip_plane = gl.GetUniformLocation(program.id, "u_clip_plane");
    return program;
  }

  ~Impl() {
    for (auto& [key, mesh] : meshes) release(mesh);
    for (auto& [key, picture] : pictures) gl.DeleteTextures(1, &picture.texture);
    for (const Program& program : programs) gl.DeleteProgram(program.id);
    release_ground();
  }

  void release(GpuMesh& mesh) {
    gl.DeleteBuffers(3, mesh.buffers);
    gl.DeleteVertexArrays(1, &mesh.vao);
  }

  void upload(GpuMesh& gpu, const RenderMesh& mesh) {
    gl.BindVertexArray(gpu.vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, gpu.buffers[0]);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.positions.size() * sizeof(Eigen::Vector3f)),
                  mesh.positions.data(), GL_DYNAMIC_DRAW);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector3f), nullptr);
    gl.EnableVertexAttribArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, gpu.buffers[1]);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.normals.size() * sizeof(Eigen::Vector3f)),
                  mesh.normals.data(), GL_DYNAMIC_DRAW);
    gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector3f), nullptr);
    gl.EnableVertexAttribArray(1);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.buffers[2]);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                  mesh.indices.data(), GL_DYNAMIC_DRAW);
    gpu.index_count = GLsizei(mesh.indices.size());
    gl.BindVertexArray(0);
  }

  GpuMesh& prepare(const DrawItem& item) {
    auto it = meshes.find(item.mesh.get());
    if (it == meshes.end()) {
      GpuMesh gpu;
      gpu.source = item.mesh;
      gl.GenVertexArrays(1, &gpu.vao);
      gl.GenBuffers(3, gpu.buffers);
      upload(gpu, *item.mesh);
      it = meshes.emplace(item.mesh.get(), gpu).first;
    } else if (item.dynamic) {
      upload(it->second, *item.mesh);
    }
    return it->second;
  }

  // Binds the item's picture (uploaded when first seen).
  void bind_picture(const std::shared_ptr<const Image>& picture) {
    auto it = pictures.find(picture.get());
    if (it == pictures.end()) {
      GpuPicture gpu{picture, 0};
      gl.GenTextures(1, &gpu.texture);
      gl.BindTexture(GL_TEXTURE_2D, gpu.texture);
      GLint alignment = 4;  // the host context's, given back
      gl.GetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
      gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
      gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, picture->width, picture->height, 0, GL_RGBA,
                    GL_UNSIGNED_BYTE, picture->rgba.data());
      gl.PixelStorei(GL_UNPACK_ALIGNMENT, alignment);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      it = pictures.emplace(picture.get(), gpu).first;
    }
    gl.BindTexture(GL_TEXTURE_2D, it->second.texture);
  }

  void release_ground() {
    gl.DeleteFramebuffers(1, &ground.framebuffer);
    gl.DeleteRenderbuffers(1, &ground.color);
    gl.DeleteRenderbuffers(1, &ground.depth);
    ground = {};
  }

  // Binds the ground's framebuffer at the given size (made or remade as needed); false when
  // the implementation refuses it.
  bool bind_ground(int width, int height) {
    if (ground.framebuffer == 0 || ground.width != width || ground.height != height) {
      release_ground();
      gl.GenFramebuffers(1, &ground.framebuffer);
      gl.BindFramebuffer(GL_FRAMEBUFFER, ground.framebuffer);
      gl.GenRenderbuffers(1, &ground.color);
      gl.BindRenderbuffer(GL_RENDERBUFFER, ground.color);
      gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, 0, GL_RGBA8, width, height);
      gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                 ground.color);
      gl.GenRenderbuffers(1, &ground.depth);
      gl.BindRenderbuffer(GL_RENDERBUFFER, ground.depth);
      gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, 0, GL_DEPTH_COMPONENT24, width, height);
      gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                 ground.depth);
      gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
      ground.width = width;
      ground.height = height;
      if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        release_ground();
        return false;
      }
      return true;
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, ground.framebuffer);
    return true;
  }

  // Meshes nobody holds any more are freed before lookups, so a new mesh at a reused address
  // is never mistaken for the old one.
  void evict_expired() {
    for (auto it = meshes.begin(); it != meshes.end();) {
      if (it->second.source.expired()) {
        release(it->second);
        it = meshes.erase(it);
      } else {
        ++it;
      }
    }
    for (auto it = pictures.begin(); it != pictures.end();) {
      if (it->second.source.expired()) {
        gl.DeleteTextures(1, &it->second.texture);
        it = pictures.erase(it);
      } else {
        ++it;
      }
    }
  }
};

Renderer::Renderer(const GlLoader& loader) : impl_(std::make_unique<Impl>(loader)) {}
Renderer::~Renderer() = default;

void Renderer::render(const DrawList& list, const OrbitCamera& camera, int width, int height) {
  render(list, view_camera(camera, height > 0 ? float(width) / float(height) : 1.0f), width,
         height);
}

void Renderer::render(const DrawList& list, const ViewCamera& camera, int width, int height) {
  auto& gl = impl_->gl;
  impl_->evict_expired();
  const Eigen::Matrix4f view_projection = camera.projection * camera.view;
  const Eigen::Vector3f eye = camera.eye;
  // Clipping stays enabled and is switched by its plane: drivers differ in whether a
  // distance the shader writes clips while GL_CLIP_DISTANCE0 is disabled.
  const Eigen::Vector4f above_ground(0.0f, 1.0f, 0.0f, 0.0f), nowhere(0.0f, 0.0f, 0.0f, 1.0f);
  const Impl::Program* current = nullptr;  // the program in use
  auto clip_to = [&](const Eigen::Vector4f& plane) {
    current = nullptr;
    for (const Impl::Program& program : impl_->programs) {
      gl.UseProgram(program.id);
      gl.Uniform4fv(program.u_clip_plane, 1, plane.data());
    }
  };
  for (const Impl::Program& program : impl_->programs) {
    gl.UseProgram(program.id);
    gl.UniformMatrix4fv(program.u_view_projection, 1, GL_FALSE, view_projection.data());
    // Programs without a use for a uniform have its location at -1, which GL ignores.
    gl.Uniform3fv(program.u_eye, 1, eye.data());
    gl.Uniform4fv(program.u_clip_plane, 1, nowhere.data());
  }
  gl.ActiveTexture(GL_TEXTURE0);  // the pictures' unit, whichever the host left active
  gl.Enable(GL_CLIP_DISTANCE0);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LEQUAL);
  gl.Disable(GL_CULL_FACE);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  auto draw = [&](const DrawItem& item) {
    if (!item.mesh || item.mesh->indices.empty()) return;
    if (item.shading == Shading::kPicture &&
        (!item.picture || item.picture->width <= 0 || item.picture->height <= 0 ||
         item.picture->rgba.size() !=
             std::size_t(item.picture->width) * std::size_t(item.picture->height) * 4))
      return;
    GpuMesh& gpu = impl_->prepare(item);
    if (item.shading == Shading::kPicture) impl_->bind_picture(item.picture);
    const Impl::Program& program = impl_->programs[static_cast<int>(item.shading)];
    if (&program != current) {
      gl.UseProgram(program.id);
      current = &program;
    }
    const Eigen::Matrix3f normal_matrix = item.model.block<3, 3>(0, 0).inverse().transpose();
    gl.UniformMatrix4fv(program.u_model, 1, GL_FALSE, item.model.data());
    gl.UniformMatrix3fv(program.u_normal_matrix, 1, GL_FALSE, normal_matrix.data());
    gl.Uniform4fv(program.u_color, 1, item.color.data());
    // Blending only where it shows: an opaque item blended still reads every pixel it covers
    // back, which a software renderer pays for per pixel.
    if (item.color.w() < 1.0f)
      gl.Enable(GL_BLEND);
    else
      gl.Disable(GL_BLEND);
    gl.BindVertexArray(gpu.vao);
    gl.DrawElements(GL_TRIANGLES, gpu.index_count, GL_UNSIGNED_INT, nullptr);
  };

  // The ground (the floor and what lies on it) is most of the picture's pixels and changes
  // only with the camera: its picture is kept and copied in, and the rest is drawn over it
  // clipped to y >= 0, which hides what is below the ground as its depth would. Only seen from
  // above, and only into a single-sampled target (a copy cannot go into a multisampled one;
  // hardware that multisamples has no need of the saving).
  Impl::GroundKey key;
  for (const DrawItem& item : list.items)
    if (item.ground && !item.overlay) key.items.push_back(item);
  GLint samples = 0;
  gl.GetIntegerv(GL_SAMPLE_BUFFERS, &samples);
  bool ground_copied = false;
  if (!key.items.empty() && eye.y() > 0.0f && samples == 0) {
    GLint draw_target = 0, read_target = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_target);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_target);
    key.width = width;
    key.height = height;
    key.view_projection = view_projection;
    key.eye = eye;
    key.background = list.background;
    Impl::GroundCache& ground = impl_->ground;
    if (ground.drawn && *ground.drawn == key) {
      ground_copied = true;
    } else if (impl_->bind_ground(width, height)) {
      gl.Viewport(0, 0, width, height);
      gl.ClearColor(list.background.x(), list.background.y(), list.background.z(), 1.0f);
      gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      for (const DrawItem& item : key.items) draw(item);
      ground.drawn = std::move(key);
      ground_copied = true;
    }
    if (ground_copied) {
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, ground.framebuffer);
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_target));
      gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_target));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_target));
  }

  gl.Viewport(0, 0, width, height);
  if (ground_copied) {
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    clip_to(above_ground);
  } else {
    gl.ClearColor(list.background.x(), list.background.y(), list.background.z(), 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  for (const DrawItem& item : list.items)
    if (!item.overlay && !(ground_copied && item.ground)) draw(item);
  if (ground_copied) clip_to(nowhere);
  gl.Disable(GL_CLIP_DISTANCE0);
  gl.Disable(GL_DEPTH_TEST);
  for (const DrawItem& item : list.items)
    if (item.overlay) draw(item);
  gl.Enable(GL_DEPTH_TEST);
  gl.Disable(GL_BLEND);
  gl.BindVertexArray(0);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  gl.UseProgram(0);
}

std::string Renderer::context_description() const {
  auto text = [&](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(impl_->gl.GetString(name));
    return std::string(s ? s : "?");
  };
  return text(GL_VENDOR) + " / " + text(GL_RENDERER) + " / " + text(GL_VERSION);
}

}  // namespace handlab::render

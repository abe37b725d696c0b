#include "core/render/renderer.h"

#include <map>
#include <stdexcept>
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
out vec3 v_world;
out vec3 v_normal;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  gl_Position = u_view_projection * world;
}
)";

// Blinn-Phong with a key light, a fill light and ambient; the floor gets a 5 cm checker
// that fades with distance so orbiting reads as motion.
constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 v_world;
in vec3 v_normal;
uniform vec4 u_color;
uniform vec3 u_eye;
uniform float u_shading;  // 0 lit, 1 checker floor, 2 unlit
out vec4 frag_color;
void main() {
  vec3 base = u_color.rgb;
  if (u_shading > 1.5) { frag_color = u_color; return; }
  if (u_shading > 0.5) {
    vec2 cell = floor(v_world.xz / 0.05);
    float checker = mod(cell.x + cell.y, 2.0);
    base *= mix(0.88, 1.0, checker);
  }
  vec3 n = normalize(v_normal);
  vec3 view = normalize(u_eye - v_world);
  if (dot(n, view) < 0.0) n = -n;
  vec3 key = normalize(vec3(0.35, 1.0, 0.55));
  vec3 fill = normalize(vec3(-0.6, 0.4, -0.3));
  float diffuse = 0.75 * max(dot(n, key), 0.0) + 0.2 * max(dot(n, fill), 0.0);
  float specular = pow(max(dot(n, normalize(key + view)), 0.0), 48.0) * 0.18;
  vec3 color = base * (0.28 + diffuse) + vec3(specular);
  frag_color = vec4(min(color, vec3(1.0)), u_color.a);
}
)";

GLuint compile(const GlFunctions& gl, GLenum type, const char* source) {
  const GLuint shader = gl.CreateShader(type);
  gl.ShaderSource(shader, 1, &source, nullptr);
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
  GlFunctions gl;
  GLuint program = 0;
  GLint u_model = -1, u_view_projection = -1, u_normal_matrix = -1, u_color = -1, u_eye = -1,
        u_shading = -1;
  std::map<const RenderMesh*, GpuMesh> meshes;

  explicit Impl(const GlLoader& loader) : gl(loader) {
    const GLuint vs = compile(gl, GL_VERTEX_SHADER, kVertexShader);
    const GLuint fs = compile(gl, GL_FRAGMENT_SHADER, kFragmentShader);
    program = gl.CreateProgram();
    gl.AttachShader(program, vs);
    gl.AttachShader(program, fs);
    gl.LinkProgram(program);
    gl.DeleteShader(vs);
    gl.DeleteShader(fs);
    GLint ok = 0;
    gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[2048] = {};
      gl.GetProgramInfoLog(program, sizeof log, nullptr, log);
      throw std::runtime_error(std::string("shader link failed: ") + log);
    }
    u_model = gl.GetUniformLocation(program, "u_model");
    u_view_projection = gl.GetUniformLocation(program, "u_view_projection");
    u_normal_matrix = gl.GetUniformLocation(program, "u_normal_matrix");
    u_color = gl.GetUniformLocation(program, "u_color");
    u_eye = gl.GetUniformLocation(program, "u_eye");
    u_shading = gl.GetUniformLocation(program, "u_shading");
  }

  ~Impl() {
    for (auto& [key, mesh] : meshes) release(mesh);
    gl.DeleteProgram(program);
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
  }
};

Renderer::Renderer(const GlLoader& loader) : impl_(std::make_unique<Impl>(loader)) {}
Renderer::~Renderer() = default;

void Renderer::render(const DrawList& list, const OrbitCamera& camera, int width, int height) {
  auto& gl = impl_->gl;
  impl_->evict_expired();
  gl.Viewport(0, 0, width, height);
  gl.ClearColor(list.background.x(), list.background.y(), list.background.z(), 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LEQUAL);
  gl.Disable(GL_CULL_FACE);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  const float aspect = height > 0 ? float(width) / float(height) : 1.0f;
  const Eigen::Matrix4f view_projection = camera.projection(aspect) * camera.view();
  const Eigen::Vector3f eye = camera.eye();
  gl.UseProgram(impl_->program);
  gl.UniformMatrix4fv(impl_->u_view_projection, 1, GL_FALSE, view_projection.data());
  gl.Uniform3fv(impl_->u_eye, 1, eye.data());

  auto draw = [&](const DrawItem& item) {
    if (!item.mesh || item.mesh->indices.empty()) return;
    GpuMesh& gpu = impl_->prepare(item);
    const Eigen::Matrix3f normal_matrix = item.model.block<3, 3>(0, 0).inverse().transpose();
    gl.UniformMatrix4fv(impl_->u_model, 1, GL_FALSE, item.model.data());
    gl.UniformMatrix3fv(impl_->u_normal_matrix, 1, GL_FALSE, normal_matrix.data());
    gl.Uniform4fv(impl_->u_color, 1, item.color.data());
    gl.Uniform1f(impl_->u_shading, static_cast<float>(item.shading));
    // Blending only where it shows: an opaque item blended still reads every pixel it covers
    // back, which a software renderer pays for per pixel.
    if (item.color.w() < 1.0f)
      gl.Enable(GL_BLEND);
    else
      gl.Disable(GL_BLEND);
    gl.BindVertexArray(gpu.vao);
    gl.DrawElements(GL_TRIANGLES, gpu.index_count, GL_UNSIGNED_INT, nullptr);
  };
  for (const DrawItem& item : list.items)
    if (!item.overlay) draw(item);
  gl.Disable(GL_DEPTH_TEST);
  for (const DrawItem& item : list.items)
    if (item.overlay) draw(item);
  gl.Enable(GL_DEPTH_TEST);
  gl.Disable(GL_BLEND);
  gl.BindVertexArray(0);
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

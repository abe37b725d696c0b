#include "app/cli/offscreen_eyes.h"

#include <memory>

#include "core/render/offscreen_context.h"

namespace handlab::cli {

xr::HeadsetView::DrawerFactory offscreen_eyes() {
  return [](int width, int height) {
    auto renderer = std::make_shared<render::OffscreenRenderer>(width, height);
    return [renderer](const render::DrawList& scene, const render::ViewCamera& camera) {
      return renderer->render(scene, camera);
    };
  };
}

}  // namespace handlab::cli

#include "game/view/match_frames.h"

#ifdef RICOCHET_HAS_RENDER
#include "game/view/match_view.h"
#include "render/draw_list.h"
#endif

namespace game {

struct MatchFrames::Impl {
  FrameOutput output;
#ifdef RICOCHET_HAS_RENDER
  std::unique_ptr<MatchView> view;
  MatchViewOptions viewOptions;
#endif
  Impl(const FrameOptions& options, const std::string& command, long ticks)
      : output(options, command, ticks, static_cast<double>(kTickSeconds)) {}
};

MatchFrames::MatchFrames(const FrameOptions& options, const std::string& command,
                         const MatchState& s, long ticks, const std::string& caption)
    : impl_(std::make_unique<Impl>(options, command, ticks)) {
#ifdef RICOCHET_HAS_RENDER
  if (!impl_->output.enabled()) return;
  impl_->view = std::make_unique<MatchView>(s, options.width, options.height);
  impl_->viewOptions.overlay = options.overlay;
  impl_->viewOptions.caption = caption;
#else
  (void)s;
  (void)caption;
#endif
}

MatchFrames::~MatchFrames() = default;

void MatchFrames::update(const MatchState& s) {
#ifdef RICOCHET_HAS_RENDER
  if (!impl_->view) return;
  impl_->view->observe(s);
  const long step = static_cast<long>(s.tick);
  if (impl_->output.due(step))
    impl_->output.add(step, impl_->view->draw(s, impl_->viewOptions), impl_->view->camera());
#else
  (void)s;
#endif
}

long long MatchFrames::framesAdded() const {
  return impl_->output.framesAdded();
}

void MatchFrames::finish() {
  impl_->output.finish();
}

}  // namespace game

#include "app/gui/session_worker.h"

#include <algorithm>

#include "core/store/study_store.h"
#include "studies/session/openxr_tracker.h"
#include "studies/session/session_runner.h"

namespace handlab::gui {

SessionWorker::SessionWorker(SessionOptions options, QObject* parent)
    : QObject(parent), options_(std::move(options)) {}

SessionWorker::~SessionWorker() {
  closing_ = true;
  control_.request_stop();
  control_.set_paused(false);
  {
    const std::lock_guard<std::mutex> lock(answer_mutex_);
    if (pending_answer_) {  // the window closes during a questionnaire: no answers
      pending_answer_->set_exception(
          std::make_exception_ptr(std::runtime_error("the questionnaire was not answered")));
      pending_answer_.reset();
    }
  }
  if (thread_.joinable()) thread_.join();
}

void SessionWorker::start() {
  if (options_.in_headset) {
    headset_ = std::make_unique<studies::SessionHeadset>(
        control_, options_.protocol.scene, options_.headset_eyes,
        [this](const std::string& line) { emit headset_said(QString::fromStdString(line)); },
        options_.openxr_hands);
    options_.real_time = true;  // the participant sees the trial as it happens
  }
  if (options_.openxr_hands) options_.tracker = studies::openxr_tracker(headset_.get());
  thread_ = std::thread([this] { run(); });
}

std::optional<xr::HeadsetCounts> SessionWorker::headset_counts() const {
  if (!headset_) return std::nullopt;
  return headset_->counts();
}

void SessionWorker::set_headset_panel(std::shared_ptr<const render::Image> picture) {
  if (headset_) headset_->set_panel(std::move(picture));
}

std::optional<xr::DisplayFrame> SessionWorker::headset_frame() const {
  if (!headset_) return std::nullopt;
  return headset_->last_frame();
}

SessionSnapshot SessionWorker::snapshot() const {
  step_waiting_ = false;
  const std::lock_guard<std::mutex> lock(mutex_);
  return snapshot_;
}

void SessionWorker::answer(std::vector<int> values) {
  const std::lock_guard<std::mutex> lock(answer_mutex_);
  if (!pending_answer_) return;
  pending_answer_->set_value(std::move(values));
  pending_answer_.reset();
}

void SessionWorker::run() {
  // Signals from this thread reach the window queued (the worker lives on the window's).
  control_.calibration = [this](const studies::CalibrationStatus& status) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      snapshot_.calibration = status;
    }
    if (!step_waiting_.exchange(true)) emit step_ready();
    emit calibration_changed(QString::fromStdString(status.message()),
                             status.state == studies::CalibrationStatus::State::kDone);
  };
  control_.trial_started = [this](const studies::TrialSetup& setup, int planned) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      snapshot_.in_trial = true;
      snapshot_.calibration.reset();
      snapshot_.position = setup.planned.position;
      snapshot_.planned = planned;
      snapshot_.block = setup.planned.block;
      snapshot_.practice = setup.planned.practice;
      snapshot_.condition = setup.condition.label;
      snapshot_.cube_size = setup.condition.cube_size;
      snapshot_.simulated_hand = setup.condition.simulated_hand;
      snapshot_.step = {};
      snapshot_.frame = {};
      snapshot_.skin.reset();
      snapshot_.flesh_nodes.clear();
    }
    if (headset_) headset_->trial_started(setup);
    emit trial_started(setup.planned.position);
  };
  control_.stepped = [this](const studies::TrialStep& step) {
    const bool soft = step.flesh && step.flesh_nodes;
    if (soft && step.flesh != skin_of_) {
      skin_of_ = step.flesh;
      skin_ =
          std::make_shared<const SoftHandSkin>(SoftHandSkin{step.flesh->render, step.flesh->tets});
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      snapshot_.step = step;
      snapshot_.step.frame = nullptr;
      snapshot_.step.flesh = nullptr;
      snapshot_.step.flesh_nodes = nullptr;
      snapshot_.frame = *step.frame;
      if (soft) {
        snapshot_.skin = skin_;
        snapshot_.flesh_nodes = *step.flesh_nodes;
      } else {
        snapshot_.skin.reset();
        snapshot_.flesh_nodes.clear();
      }
      ++snapshot_.steps;
      snapshot_.stepped_at = std::chrono::steady_clock::now();
      if (options_.frame_arrival) snapshot_.frame_arrival_ns = options_.frame_arrival();
    }
    if (headset_) headset_->stepped(step);
    if (!step_waiting_.exchange(true)) emit step_ready();
  };
  control_.trial_ended = [this](const studies::TrialSetup& setup, const studies::TrialRun& run) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      snapshot_.in_trial = false;
    }
    emit trial_ended(setup.planned.position, run.success, run.completion_time_s, run.aborted);
  };
  control_.decided = [this](const studies::TrialDecision& d, const std::string& error) {
    const QString what = d.kind == studies::TrialDecision::Kind::kRedo ? tr("Redo") : tr("Skip");
    emit decided(error.empty() ? tr("%1 of trial %2 recorded: %3")
                                     .arg(what)
                                     .arg(d.position + 1)
                                     .arg(QString::fromStdString(d.reason))
                               : tr("%1 of trial %2 refused: %3")
                                     .arg(what)
                                     .arg(d.position + 1)
                                     .arg(QString::fromStdString(error)));
  };
  control_.holding = [this] { emit holding(); };

  try {
    store::StudyStore store(options_.database.toStdString());
    // The display keeps a core of its own (on two cores the simulator gets one).
    const int threads = std::clamp(int(std::thread::hardware_concurrency()) - 1, 1, 2);
    studies::PipelineTrialDriver driver(options_.tracker, 120.0, options_.world, threads);
    driver.set_real_time(options_.real_time);
    studies::QuestionnaireResponder responder;
    if (const auto own = options_.tracker->own_answers()) {
      responder = *own;
    } else {
      responder = [this](const studies::SeenQuestionnaire& asked, const studies::TrialRun&) {
        std::future<std::vector<int>> answers;
        {
          const std::lock_guard<std::mutex> lock(answer_mutex_);
          if (closing_) throw std::runtime_error("the session was closed");
          pending_answer_.emplace();
          answers = pending_answer_->get_future();
        }
        // The experimenter's dialog names the trial's condition (the one running).
        QString label;
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          label = QString::fromStdString(snapshot_.condition);
        }
        emit questionnaire_requested(asked.position, label);
        return answers.get();
      };
    }
    studies::SessionRunner runner(store, driver, responder);
    runner.attach(&control_);
    const std::string tracker = options_.world == studies::WorldKind::kSoftHand
                                    ? options_.tracker->name() + " (soft hand)"
                                    : options_.tracker->name();
    const studies::SessionReport report =
        runner.run(options_.participant, tracker, options_.resume);
    if (headset_) headset_->close();
    finished_ = true;
    emit finished(report.schedule_complete, report.stopped, report.trials_run);
  } catch (const std::exception& e) {
    if (headset_) headset_->close();
    finished_ = true;
    emit failed(QString::fromStdString(e.what()));
  }
}

}  // namespace handlab::gui

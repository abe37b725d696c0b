#include "app/gui/session_page.h"

#include <algorithm>

#include <QCheckBox>
#include <QComboBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QInputDialog>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPixmap>
#include <QPushButton>
#include <QSpinBox>
#include <QTime>
#include <QTimer>
#include <QVBoxLayout>

#include "app/gui/headset_panel.h"
#include "app/gui/participant_window.h"
#include "app/gui/questionnaire_dialog.h"
#include "app/gui/questionnaire_form.h"
#include "app/gui/scene_view.h"
#include "app/gui/session_worker.h"
#include "app/gui/trial_phase_text.h"
#include "app/gui/trial_replay_bar.h"
#include "app/live/live_frames.h"
#include "core/hand/simulated_hand.h"
#include "core/render/frame_drawing.h"
#include "core/render/hand_drawing.h"
#include "core/render/scene_drawing.h"
#include "core/store/study_store.h"
#include "core/task/cube_task.h"
#include "studies/session/session_runner.h"

namespace handlab::gui {

SessionPage::SessionPage(QWidget* parent) : QWidget(parent) {
  auto* layout = new QHBoxLayout(this);
  auto* left = new QVBoxLayout;
  view_ = new SceneView;
  left->addWidget(view_, 1);
  replay_ = new TrialReplayBar;
  replay_->hide();
  left->addWidget(replay_);
  // In the headset: what it shows, its left eye's last image as read back from it.
  headset_mirror_ = new QLabel;
  headset_mirror_->setObjectName("headset_mirror");
  headset_mirror_->setToolTip(tr("What the headset shows: its left eye, as read back from it"));
  headset_mirror_->setAlignment(Qt::AlignCenter);
  headset_mirror_->hide();
  left->addWidget(headset_mirror_);
  mirror_timer_ = new QTimer(this);
  mirror_timer_->setInterval(100);
  connect(mirror_timer_, &QTimer::timeout, this, &SessionPage::mirror_headset);
  layout->addLayout(left, 3);
  connect(replay_, &TrialReplayBar::moment, this,
          [this](std::shared_ptr<const render::DrawList> picture, const store::FrameRecord& frame) {
            view_->set_frame(std::move(picture));
            state_->setText(phase_text(task::TaskPhase(frame.task_phase)));
            clock_->setText(tr("%1 s").arg(frame.time, 0, 'f', 1));
          });
  connect(replay_, &TrialReplayBar::closed, this, [this] {
    view_->set_frame(nullptr);  // the idle scene again
    for (QLabel* label : {trial_, state_, clock_, counts_}) label->setText(QStringLiteral("–"));
  });

  auto* side = new QVBoxLayout;
  layout->addLayout(side, 1);

  setup_ = new SessionSetup;
  side->addWidget(setup_);

  auto* calibration = new QGroupBox(tr("Calibration"));
  auto* cal_layout = new QVBoxLayout(calibration);
  auto* how =
      new QLabel(tr("The participant holds the right hand open, fingers spread, "
                    "palm down and still over the table for two seconds; the "
                    "countdown starts again if the hand moves or closes."));
  how->setWordWrap(true);
  cal_layout->addWidget(how);
  calibration_ = new QLabel(tr("Not calibrated: it is the session's first step."));
  calibration_->setObjectName("calibration_state");
  calibration_->setWordWrap(true);
  QFont bold = calibration_->font();
  bold.setBold(true);
  calibration_->setFont(bold);
  cal_layout->addWidget(calibration_);
  side->addWidget(calibration);

  auto* panel = new QGroupBox(tr("Trial"));
  auto* panel_form = new QFormLayout(panel);
  trial_ = new QLabel("–");
  trial_->setObjectName("trial");
  state_ = new QLabel("–");
  state_->setObjectName("trial_state");
  clock_ = new QLabel("–");
  counts_ = new QLabel("–");
  panel_form->addRow(tr("Trial"), trial_);
  panel_form->addRow(tr("State"), state_);
  panel_form->addRow(tr("Clock"), clock_);
  panel_form->addRow(tr("Grasps, drops"), counts_);
  side->addWidget(panel);

  auto* buttons = new QGridLayout;
  start_ = new QPushButton(tr("Start (F5)"));
  start_->setShortcut(Qt::Key_F5);
  pause_ = new QPushButton(tr("Pause (F6)"));
  pause_->setShortcut(Qt::Key_F6);
  pause_->setCheckable(true);
  stop_ = new QPushButton(tr("Stop (F8)"));
  stop_->setShortcut(Qt::Key_F8);
  redo_ = new QPushButton(tr("Redo… (Ctrl+R)"));
  redo_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_R));
  skip_ = new QPushButton(tr("Skip… (Ctrl+K)"));
  skip_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_K));
  buttons->addWidget(start_, 0, 0);
  buttons->addWidget(pause_, 0, 1);
  buttons->addWidget(stop_, 0, 2);
  buttons->addWidget(redo_, 1, 0);
  buttons->addWidget(skip_, 1, 1);
  side->addLayout(buttons);
  connect(start_, &QPushButton::clicked, this, [this] {
    const QString error = start_session();
    if (!error.isEmpty()) append_log(tr("Not started: %1").arg(error));
  });
  connect(pause_, &QPushButton::clicked, this, &SessionPage::toggle_pause);
  connect(stop_, &QPushButton::clicked, this, &SessionPage::stop_session);
  auto ask = [this](bool redo) {
    bool ok = false;
    const int trial =
        QInputDialog::getInt(this, redo ? tr("Redo a Trial") : tr("Skip a Trial"),
                             tr("Trial number (as the schedule shows it):"), 1, 1, 10000, 1, &ok);
    if (!ok) return;
    const QString reason = QInputDialog::getText(
        this, redo ? tr("Redo a Trial") : tr("Skip a Trial"), tr("Reason (kept in the record):"),
        QLineEdit::Normal, QString(), &ok);
    if (!ok) return;
    const QString error = redo ? redo_trial(trial - 1, reason) : skip_trial(trial - 1, reason);
    if (!error.isEmpty()) append_log(error);
  };
  connect(redo_, &QPushButton::clicked, this, [ask] { ask(true); });
  connect(skip_, &QPushButton::clicked, this, [ask] { ask(false); });

  log_ = new QListWidget;
  log_->setObjectName("session_log");
  side->addWidget(log_, 1);

  connect(view_, &SceneView::picture_shown, this, [this] { display_.picture_shown(); });
  set_running(false);
}

SessionPage::~SessionPage() {
  worker_.reset();  // the session stops before the live client whose frames it reads goes
}

void SessionPage::set_study(OpenStudy study) {
  // Read first: a study whose protocol cannot be read leaves the page as it was.
  std::optional<studies::Protocol> protocol;
  if (study.is_open()) protocol = studies::stored_protocol(*study.store);
  worker_.reset();
  replay_->set_playing(false);
  replay_->hide();
  study_ = std::move(study);
  protocol_ = std::move(protocol);
  if (protocol_) {
    view_->set_layout(protocol_->scene);
    setup_->use_defaults(*protocol_);
  }
  set_running(false);
}

void SessionPage::set_participants(const QStringList& ids, const QString& selected) {
  // A running session's participant stays chosen.
  const QString keep =
      selected.isEmpty() || session_running() ? setup_->participant_box()->currentText() : selected;
  setup_->participant_box()->clear();
  setup_->participant_box()->addItems(ids);
  if (ids.contains(keep)) setup_->participant_box()->setCurrentText(keep);
}

bool SessionPage::session_running() const {
  return worker_ && worker_->running();
}

void SessionPage::set_leap_address(const QString& address) {
  setup_->set_leap_address(address);
}

QString SessionPage::replay_trial(const QString& participant, int position, int attempt) {
  if (!study_.is_open()) return tr("no study is open");
  if (session_running()) return tr("a session is running: replay its trials after it");
  try {
    store::StudyStore& store = *study_.store;
    replay_->load(studies::load_trial_replay(store, participant.toStdString(), position, attempt));
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
  if (view_->layout().cube_size != replay_->replay()->layout.cube_size)
    view_->set_layout(replay_->replay()->layout);
  setup_->participant_box()->setCurrentText(participant);
  const studies::TrialReplay& r = *replay_->replay();
  trial_->setText(
      tr("%1, %2 (replay)").arg(r.position + 1).arg(QString::fromStdString(r.condition)));
  counts_->setText(QStringLiteral("–"));
  replay_->show();
  return {};
}

QString SessionPage::start_session() {
  if (!study_.is_open() || !protocol_) return tr("no study is open");
  if (session_running()) return tr("a session is running");
  if (setup_->participant_box()->currentText().isEmpty()) return tr("choose a participant");
  // A replay gives the view back to the session.
  replay_->set_playing(false);
  replay_->hide();
  SessionOptions options;
  options.database = study_.path;  // the session's thread opens its own connection
  options.protocol = *protocol_;
  if (const QString error = setup_->fill(options, live_stats_); !error.isEmpty()) return error;
  {
    store::StudyStore& store = *study_.store;
    options.resume = store.has_started(options.participant);
    if (!store.next_trial(options.participant) && !store.has_running_session(options.participant))
      return tr("%1 has done every planned trial").arg(setup_->participant_box()->currentText());
  }
  try {
    worker_ = std::make_unique<SessionWorker>(std::move(options));
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
  SessionWorker* w = worker_.get();
  connect_worker(w);
  try {
    w->start();  // the headset and the OpenXR hands opened first, where chosen
  } catch (const std::exception& e) {
    worker_.reset();
    return QString::fromStdString(e.what());
  }
  calibration_->setText(tr("Calibrating: hold the right hand open and still over the table."));
  display_.start(live_stats_);
  last_drawn_step_ = -1;
  headset_text_.clear();
  headset_mirror_->setVisible(w->in_headset());
  if (w->in_headset()) mirror_timer_->start();
  set_running(true);
  append_log(tr("Session of %1 started (%2, %3)")
                 .arg(setup_->participant_box()->currentText(), setup_->tracker_name(),
                      setup_->display_box()->currentText()));
  emit session_started();
  return {};
}

// What the page shows of the session, from the worker's signals (queued from its thread).
void SessionPage::connect_worker(SessionWorker* w) {
  connect(w, &SessionWorker::step_ready, this, &SessionPage::refresh_picture);
  connect(w, &SessionWorker::calibration_changed, this, [this](const QString& message, bool) {
    calibration_->setText(message);
    if (participant_window_) participant_window_->set_instruction(message);
    show_in_headset(message);
  });
  connect(w, &SessionWorker::trial_started, this, [this](int position) {
    const auto snap = worker_->snapshot();
    trial_->setText(tr("%1 of %2, %3, %4")
                        .arg(position + 1)
                        .arg(snap.planned)
                        .arg(snap.practice ? tr("practice") : tr("block %1").arg(snap.block))
                        .arg(QString::fromStdString(snap.condition)));
    append_log(
        tr("%1 trial %2 started").arg(QTime::currentTime().toString("HH:mm:ss")).arg(position + 1));
  });
  connect(w, &SessionWorker::trial_ended, this,
          [this](int position, bool success, double seconds, bool aborted) {
            append_log(
                aborted ? tr("trial %1 stopped (kept as aborted; it runs again)").arg(position + 1)
                : success ? tr("trial %1 done in %2 s").arg(position + 1).arg(seconds, 0, 'f', 2)
                          : tr("trial %1 timed out").arg(position + 1));
            emit study_changed();
          });
  connect(w, &SessionWorker::questionnaire_requested, this, &SessionPage::show_questionnaire);
  connect(w, &SessionWorker::decided, this, [this](const QString& message) {
    append_log(message);
    emit study_changed();
  });
  connect(w, &SessionWorker::holding, this,
          [this] { append_log(tr("paused before the next trial")); });
  connect(w, &SessionWorker::finished, this, [this](bool complete, bool stopped, int run) {
    const QString summary = complete ? tr("Session finished: every trial done (%1 run).").arg(run)
                            : stopped
                                ? tr("Session stopped after %1 trial(s); resume to go on.").arg(run)
                                : tr("Session ended after %1 trial(s).").arg(run);
    append_log(summary);
    set_running(false);
    emit study_changed();
    emit session_ended(summary);
  });
  connect(w, &SessionWorker::failed, this, [this](const QString& error) {
    append_log(tr("Session failed: %1").arg(error));
    set_running(false);
    emit study_changed();
    emit session_ended(tr("Session failed: %1").arg(error));
  });
  // The headset taken off pauses the session, put back on resumes it: the button follows.
  connect(w, &SessionWorker::headset_said, this, [this](const QString& message) {
    append_log(message);
    if (worker_) pause_->setChecked(worker_->control().paused());
  });
}

void SessionPage::toggle_pause() {
  if (!session_running()) {
    pause_->setChecked(false);
    return;
  }
  const bool paused = !worker_->control().paused();
  worker_->control().set_paused(paused);
  pause_->setChecked(paused);
  append_log(paused ? tr("pause requested: the session holds after this trial") : tr("resumed"));
}

void SessionPage::stop_session() {
  if (!session_running()) return;
  worker_->control().request_stop();
  append_log(tr("stop requested"));
}

QString SessionPage::redo_trial(int position, const QString& reason) {
  if (reason.trimmed().isEmpty()) return tr("A redo needs a reason.");
  if (session_running()) {
    worker_->control().decide(
        {studies::TrialDecision::Kind::kRedo, position, reason.toStdString()});
    append_log(tr("redo of trial %1 requested (applied after this trial)").arg(position + 1));
    return {};
  }
  try {
    store::StudyStore& store = *study_.store;
    store.redo_trial(setup_->participant_box()->currentText().toStdString(), position,
                     reason.toStdString());
  } catch (const std::exception& e) {
    return tr("Redo refused: %1").arg(QString::fromStdString(e.what()));
  }
  append_log(tr("trial %1 will run again: %2").arg(position + 1).arg(reason));
  emit study_changed();
  return {};
}

QString SessionPage::skip_trial(int position, const QString& reason) {
  if (reason.trimmed().isEmpty()) return tr("A skip needs a reason.");
  if (session_running()) {
    worker_->control().decide(
        {studies::TrialDecision::Kind::kSkip, position, reason.toStdString()});
    append_log(tr("skip of trial %1 requested (applied after this trial)").arg(position + 1));
    return {};
  }
  try {
    store::StudyStore& store = *study_.store;
    studies::skip_trial_between_sessions(store,
                                         setup_->participant_box()->currentText().toStdString(),
                                         position, reason.toStdString());
  } catch (const std::exception& e) {
    return tr("Skip refused: %1").arg(QString::fromStdString(e.what()));
  }
  append_log(tr("trial %1 skipped: %2").arg(position + 1).arg(reason));
  emit study_changed();
  return {};
}

void SessionPage::set_running(bool running) {
  if (!running) mirror_timer_->stop();  // its last picture stays
  start_->setEnabled(!running && study_.is_open());
  pause_->setEnabled(running);
  stop_->setEnabled(running);
  redo_->setEnabled(study_.is_open());
  skip_->setEnabled(study_.is_open());
  setup_->set_running(running);
  if (!running) pause_->setChecked(false);
}

void SessionPage::append_log(const QString& line) {
  log_->addItem(line);
  log_->scrollToBottom();
}

void SessionPage::set_participant_window(ParticipantWindow* window) {
  if (window == participant_window_) return;
  if (participant_window_) participant_window_->disconnect(this);
  participant_window_ = window;
  // Closed while asking: the questions go on over the experimenter's window, answers kept.
  connect(window, &ParticipantWindow::questionnaire_left, this, [this](QuestionnaireForm* form) {
    form->setStyleSheet({});
    auto* dialog = new QuestionnaireDialog(form, this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    append_log(tr("the participant's window closed: the questionnaire continues here"));
    dialog->open();
  });
}

void SessionPage::show_questionnaire(int position, const QString&) {
  if (!worker_ || !protocol_) return;
  // Where the participant looks: the headset (its panel shows the dialog over this window,
  // answered with the keys), their window when it is open, else a dialog over this one.
  const bool in_headset = worker_->in_headset();
  const bool at_participant =
      !in_headset && participant_window_ && participant_window_->isVisible();
  QuestionnaireDialog* dialog =
      at_participant ? nullptr : new QuestionnaireDialog(*protocol_, position + 1, this);
  QuestionnaireForm* form =
      dialog ? dialog->form() : new QuestionnaireForm(*protocol_, true, participant_window_);
  questionnaire_ = form;
  if (in_headset) {
    connect(form, &QuestionnaireForm::changed, this, [this, form] {
      if (worker_) worker_->set_headset_panel(widget_panel(*form));
    });
  }
  connect(form, &QuestionnaireForm::saved, this, [this, form, dialog] {
    if (worker_) worker_->answer(form->answers());
    headset_text_.clear();
    show_in_headset(tr("Please wait."));
    questionnaire_ = nullptr;
    if (dialog)
      dialog->deleteLater();
    else
      participant_window_->end_questionnaire();
    append_log(tr("questionnaire answered"));
  });
  if (dialog) {
    dialog->open();
    if (in_headset) {
      worker_->set_headset_panel(widget_panel(*form));
      state_->setText(tr("Awaiting the participant's answers (in the headset)"));
    }
  } else {
    participant_window_->show_questionnaire(form);
    state_->setText(tr("Awaiting the participant's answers (in their window)"));
    append_log(tr("trial %1: questionnaire in the participant's window, answers awaited")
                   .arg(position + 1));
  }
  emit questionnaire_opened(form);
}

void SessionPage::mirror_headset() {
  const auto frame = worker_ ? worker_->headset_frame() : std::nullopt;
  if (!frame || !frame->drawn) return;
  const render::Image& eye = frame->read_back[0];
  const QImage image(eye.rgba.data(), eye.width, eye.height, eye.width * 4,
                     QImage::Format_RGBA8888);
  // A copy: `image` stands on the frame's pixels, which go with it.
  headset_mirror_->setPixmap(QPixmap::fromImage(
      image.scaledToHeight(std::min(eye.height, 240), Qt::SmoothTransformation).copy()));
}

void SessionPage::show_in_headset(const QString& instruction) {
  if (!worker_ || !worker_->in_headset() || instruction == headset_text_) return;
  headset_text_ = instruction;
  worker_->set_headset_panel(text_panel(instruction));
}

void SessionPage::refresh_picture() {
  if (!worker_ || !protocol_) return;
  const SessionSnapshot snap = worker_->snapshot();
  if (snap.calibration) {
    // The tracked hand as it arrives, its palm placed where the calibration puts it.
    task::SceneLayout layout = protocol_->scene;
    render::DrawList list = render::draw_task_scene(layout, task::cube_start_pose(layout));
    if (const auto* hand = snap.calibration->frame.hand(tracking::Side::kRight)) {
      const Eigen::Isometry3d place(
          Eigen::Translation3d(layout.zone_a + Eigen::Vector3d(0, 0.12, 0) - hand->palm_position));
      render::draw_tracked_hand(list, *hand, place, Eigen::Vector4f(0.35f, 0.75f, 0.95f, 1.0f));
    }
    auto shared = std::make_shared<const render::DrawList>(std::move(list));
    view_->set_frame(shared);
    if (participant_window_) participant_window_->set_frame(layout, shared);
    return;
  }
  if (snap.steps == last_drawn_step_ || snap.frame.bone_positions.empty()) return;
  last_drawn_step_ = snap.steps;
  if (hand_meshes_.capsules.empty() || hand_shape_.length != snap.simulated_hand.length ||
      hand_shape_.hand_breadth() != snap.simulated_hand.hand_breadth()) {
    hand_meshes_ = render::make_bone_meshes(hand::build_simulated_hand(snap.simulated_hand));
    hand_shape_ = snap.simulated_hand;
  }
  task::SceneLayout layout = protocol_->scene;
  layout.cube_size = snap.cube_size;
  // On the soft hand the participant sees its skin, as the simulator deforms it.
  auto list = std::make_shared<const render::DrawList>(
      snap.skin ? render::draw_soft_hand_frame(layout, snap.skin->surface, snap.skin->tets,
                                               snap.flesh_nodes, snap.frame)
                : render::draw_stored_frame(layout, hand_meshes_, snap.frame));
  if (view_->layout().cube_size != layout.cube_size) view_->set_layout(layout);
  view_->set_frame(list);
  if (participant_window_) {
    participant_window_->set_frame(layout, list);
    participant_window_->set_instruction(instruction(snap.step.phase));
  }
  show_in_headset(instruction(snap.step.phase));
  state_->setText(phase_text(snap.step.phase));
  clock_->setText(tr("%1 s").arg(snap.step.time, 0, 'f', 1));
  counts_->setText(tr("%1, %2").arg(snap.step.grasps).arg(snap.step.drops));

  display_.picture_made(snap.frame_arrival_ns, snap.stepped_at);
}

DisplayStats SessionPage::display_stats() const {
  return display_.stats();
}

void SessionPage::reset_display_stats() {
  display_.reset();
}

}  // namespace handlab::gui

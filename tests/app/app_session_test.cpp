// The experimenter's app end to end, through its real widgets: a study created from the
// shipped protocol, a participant added through the form (and a duplicate id refused), the
// session set up, calibrated and run on the soft hand with the scripted participant through
// the trial panel,
// every questionnaire answered in its dialog with the keys, one trial redone with a reason;
// then the study file read back and checked against what was done. And the app process
// killed during a trial, the study reopened in a new window and the session resumed there. And
// a session of the 3 × 3 example design.
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QProcess>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QSpinBox>
#include <QTabWidget>
#include <QTableView>
#include <QTemporaryDir>
#include <QTest>
#include <QTextBrowser>
#include <QTimer>

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <thread>

#include "app/gui/analysis_page.h"
#include "app/gui/main_window.h"
#include "app/gui/participant_form.h"
#include "app/gui/participant_window.h"
#include "app/gui/participants_page.h"
#include "app/gui/questionnaire_form.h"
#include "app/gui/scene_view.h"
#include "app/gui/session_page.h"
#include "app/gui/session_worker.h"
#include "app/gui/study_home.h"
#include "app/gui/trial_replay_bar.h"
#include "core/render/draw_list.h"
#include "core/store/study_store.h"
#include "core/util/csv.h"
#include "studies/protocol/protocol.h"
#include "studies/session/enrolment.h"
#include "studies/session/session_runner.h"
#include "tests/app/enrol_p01.h"
#include "tests/app/view_cells.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

using handlab::gui::testing::enrol_p01;
using handlab::gui::testing::view_cell;
using handlab::gui::testing::view_rows;

namespace handlab::gui {
namespace {

const QString kProtocol = QString(HANDLAB_SOURCE_DIR) + "/studies/fine-manipulation-2021.json";

// Runs `fill` on the modal form once it is up (exec() blocks the test until it closes).
void when_form_opens(std::function<void(ParticipantForm*)> fill) {
  QTimer::singleShot(0, [fill] {
    auto* form = qobject_cast<ParticipantForm*>(QApplication::activeModalWidget());
    ASSERT_NE(form, nullptr);
    fill(form);
  });
}

// The session page set for P01 and the scripted participant in `world`, as fast as it goes.
SessionPage* scripted_session(MainWindow& window, studies::WorldKind world) {
  SessionPage* page = window.session();
  page->participant_box()->setCurrentText("P01");
  page->tracker_box()->setCurrentIndex(3);  // scripted
  page->world_box()->setCurrentIndex(page->world_box()->findData(int(world)));
  page->real_time_box()->setChecked(false);
  return page;
}

TEST(AppSession, RunsAWholeSessionFromTheWindow) {
  const QString db = QString::fromStdString(test::fresh_path("app_session.db"));
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  // With practice trials: the session runs them and the exports leave them out.
  ASSERT_EQ(window.create_study(QString::fromStdString(test::study_with_practice()), db),
            QString());
  EXPECT_TRUE(window.windowTitle().startsWith("app_session.db"));
  EXPECT_GT(view_rows(window.home()->summary()), 10) << "the protocol's summary";

  // Add P01 through the form.
  when_form_opens([](ParticipantForm* form) {
    EXPECT_FALSE(form->buttons()->button(QDialogButtonBox::Ok)->isEnabled()) << "empty form";
    QTest::keyClicks(form->id_edit(), "P01");
    form->age_box()->setValue(27);
    form->sex_box()->setCurrentIndex(form->sex_box()->findData("F"));
    form->handedness_box()->setCurrentIndex(form->handedness_box()->findData("right"));
    form->hand_length_box()->setValue(9.0);  // cm: refused
    EXPECT_TRUE(form->problems().join(" ").contains("between 10 and 30 cm"));
    form->hand_length_box()->setValue(18.4);
    form->vr_box()->setCurrentText("some");
    QTest::keyClicks(form->notes_edit(), "wears glasses, \"tired\"");
    EXPECT_TRUE(form->problems().isEmpty()) << form->problems().join(";").toStdString();
    QTest::mouseClick(form->buttons()->button(QDialogButtonBox::Ok), Qt::LeftButton);
  });
  EXPECT_EQ(window.participants()->add_participant(), "P01");
  // The same id again is refused with the reason, and nothing is enrolled.
  bool refused = false;
  when_form_opens([&](ParticipantForm* form) {
    QTest::keyClicks(form->id_edit(), "P01");
    refused = form->problems().join(" ").contains("already enrolled") &&
              !form->buttons()->button(QDialogButtonBox::Ok)->isEnabled();
    form->reject();
  });
  EXPECT_EQ(window.participants()->add_participant(), "");
  EXPECT_TRUE(refused);
  ASSERT_EQ(view_rows(window.participants()->table()), 1);
  EXPECT_EQ(view_cell(window.participants()->table(), 0, 4), "18.4");
  window.participants()->select("P01");
  EXPECT_EQ(view_rows(window.participants()->schedule()), 24);

  // Set up: the scripted participant on the soft hand, as fast as it goes.
  SessionPage* page = scripted_session(window, studies::WorldKind::kSoftHand);
  std::vector<std::vector<int>> answered;
  int questionnaires = 0;
  QObject::connect(page, &SessionPage::questionnaire_opened, [&](QuestionnaireForm* dialog) {
    // Answered with the keys: 4, 2, 5 for the first trial, then 3s; Enter saves.
    const std::vector<int> keys =
        questionnaires++ == 0 ? std::vector<int>{4, 2, 5} : std::vector<int>{3, 3, 3};
    QTimer::singleShot(0, [dialog, keys, &answered] {
      QTest::keyClick(dialog, Qt::Key_Return);  // not yet: nothing answered
      EXPECT_TRUE(dialog->isVisible());
      for (int k : keys) QTest::keyClick(dialog, Qt::Key(Qt::Key_0 + k));
      answered.push_back(dialog->answers());
      QTest::keyClick(dialog, Qt::Key_Return);
    });
  });
  // After trial 3, the experimenter asks for trial 2 to be redone.
  bool redo_asked = false;
  QSignalSpy ended(page, &SessionPage::session_ended);
  QTest::mouseClick(page->start_button(), Qt::LeftButton);
  ASSERT_TRUE(page->session_running()) << page->log()->count();
  // What the view showed of the first trial: the soft hand as its skin (one mesh that
  // deforms, not the bones' capsules).
  std::size_t skin_triangles = 0, skins = 0;
  // With `page` as the context the slot runs on the window's thread, as a click would.
  QObject::connect(page->worker(), &SessionWorker::trial_ended, page,
                   [&](int position, bool, double, bool) {
                     if (position == 0 && page->view()->frame())
                       for (const render::DrawItem& item : page->view()->frame()->items)
                         if (item.dynamic) {
                           ++skins;
                           skin_triangles = item.mesh->indices.size() / 3;
                         }
                     if (position == 2 && !redo_asked) {
                       redo_asked = true;
                       EXPECT_EQ(page->redo_trial(1, "participant looked away"), QString());
                     }
                   });
  ASSERT_TRUE(ended.wait(240000)) << "the session ends";
  EXPECT_TRUE(ended.front().front().toString().contains("every trial done"))
      << ended.front().front().toString().toStdString();
  EXPECT_TRUE(page->calibration_label()->text().startsWith("Calibrated: scale"));
  EXPECT_EQ(questionnaires, 4);
  EXPECT_EQ(skins, 1u);
  EXPECT_GT(skin_triangles, 5000u);
  EXPECT_EQ(view_cell(window.participants()->table(), 0, 9), "complete");

  // The study file, reopened, holds what was done.
  store::StudyStore store(db.toStdString());
  const auto p = store.participant("P01");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->age, 27);
  EXPECT_DOUBLE_EQ(p->hand_length, 0.184);
  EXPECT_EQ(p->notes, "wears glasses, \"tired\"");
  {
    store::Statement s = store.database().prepare("SELECT tracker FROM session");
    ASSERT_TRUE(s.step());
    EXPECT_EQ(s.column_text(0), "scripted (soft hand)");
  }
  const auto trials = store.trials("P01");
  ASSERT_EQ(trials.size(), 25u);
  int redone = 0;
  for (const auto& t : trials)
    if (t.status == store::TrialStatus::kRedone) {
      ++redone;
      EXPECT_EQ(t.position, 1);
      EXPECT_EQ(t.reason, "participant looked away");
    }
  EXPECT_EQ(redone, 1);
  std::map<int, std::vector<int>> answers_by_trial;
  {
    store::Statement s = store.database().prepare(
        "SELECT t.id, a.value FROM answer a JOIN trial t ON t.id = a.trial_id ORDER BY t.id, "
        "a.rowid");
    while (s.step()) answers_by_trial[int(s.column_int64(0))].push_back(int(s.column_int64(1)));
  }
  ASSERT_EQ(answers_by_trial.size(), 4u);
  EXPECT_EQ(answers_by_trial.begin()->second, (std::vector<int>{4, 2, 5}));
  ASSERT_EQ(answered.size(), 4u);

  // Exports read back through the data table (RFC 4180: the quoted notes stay one cell).
  const QString csv = QString::fromStdString(test::fresh_path("app_trials.csv"));
  ASSERT_EQ(window.export_table(csv, MainWindow::Table::kTrials), QString());
  const auto rows = util::parse_csv(test::file_bytes(csv.toStdString()));
  EXPECT_EQ(rows.size(), 1u + 20u) << "header and the 20 block trials";
  ASSERT_EQ(window.open_data_table(csv), QString());
  auto* table = window.findChild<QTableView*>("data_table");
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(view_rows(table), 20);
  // File > Export Frames: a row for every logged step of those 20 trials.
  const QString frames_csv = QString::fromStdString(test::fresh_path("app_frames.csv"));
  ASSERT_EQ(window.export_table(frames_csv, MainWindow::Table::kFrames), QString());
  std::size_t steps = 0;
  const auto plan = store.plan("P01");
  for (const auto& t : trials)
    if (!plan[std::size_t(t.position)].practice &&
        (t.status == store::TrialStatus::kCompleted || t.status == store::TrialStatus::kTimeout))
      steps += std::size_t(t.frames);
  EXPECT_GT(steps, 20u * 120u);
  EXPECT_EQ(util::parse_csv(test::file_bytes(frames_csv.toStdString())).size(), 1 + steps);

  // File > Export Report... writes what `handlab-cli report` writes; the Analysis view shows
  // the same text and tables (one participant: the ANOVA says why it was not computed).
  const QString folder = QString::fromStdString(test::fresh_path("app_report"));
  ASSERT_EQ(window.export_report(folder), QString());
  const std::string html = test::file_bytes(folder.toStdString() + "/report.html");
  EXPECT_NE(html.find("data-src=\"/data_quality/planned\">20<"), std::string::npos);
  EXPECT_NE(html.find("after 1 practice trial per condition that are not analysed."),
            std::string::npos);
  EXPECT_EQ(test::file_bytes(folder.toStdString() + "/report.pdf").rfind("%PDF", 0), 0u);
  auto* analysis = window.findChild<AnalysisPage*>();
  ASSERT_NE(analysis, nullptr);
  QSignalSpy analysed(analysis, &AnalysisPage::ready);
  analysis->run();
  ASSERT_TRUE(analysed.wait(20000));
  const QString shown = analysis->tables()->toPlainText();
  EXPECT_TRUE(shown.contains("Data quality")) << shown.toStdString();
  EXPECT_TRUE(shown.contains("fewer than two participants")) << shown.toStdString();

  // A trial played back from the Participants view: Replay Trial on the first trial shows it
  // in the session view from its first moment, playing; the slider at its end shows the cube
  // where the log has it last and the task's state then.
  ParticipantsPage* people = window.participants();
  people->select("P01");
  EXPECT_FALSE(people->replay_button()->isEnabled()) << "no trial chosen yet";
  people->schedule()->selectRow(0);
  ASSERT_TRUE(people->replay_button()->isEnabled());
  QTest::mouseClick(people->replay_button(), Qt::LeftButton);
  EXPECT_EQ(window.tabs()->currentWidget(), page);
  TrialReplayBar* bar = page->replay_bar();
  ASSERT_TRUE(bar->isVisible());
  ASSERT_NE(bar->replay(), nullptr);
  EXPECT_EQ(bar->replay()->position, 0);
  EXPECT_TRUE(bar->playing());
  EXPECT_EQ(int(bar->replay()->frames.size()), trials[0].frames);
  bar->slider()->setValue(bar->slider()->maximum());
  EXPECT_FALSE(bar->playing()) << "moving the slider holds the playback";
  EXPECT_NEAR(bar->time(), bar->replay()->duration(), 1e-3);
  const store::FrameRecord& last = bar->replay()->frames.back();
  bool cube_drawn = false;
  for (const render::DrawItem& item : page->view()->frame()->items)
    cube_drawn |= (item.model.block<3, 1>(0, 3) - last.cube_position).norm() < 1e-6f;
  EXPECT_TRUE(cube_drawn) << "the cube where the last frame has it";
  EXPECT_EQ(page->state_label()->text(),
            trials[0].status == store::TrialStatus::kCompleted ? "done" : "timed out");
  // Every trial of the finished session can be played back; one outside the schedule is
  // refused with the reason.
  people->schedule()->selectRow(23);
  EXPECT_TRUE(people->replay_button()->isEnabled()) << "every trial ran";
  EXPECT_NE(page->replay_trial("P01", 30), QString());
  // Closed, the replay gives the view its idle scene back.
  QTest::mouseClick(bar->close_button(), Qt::LeftButton);
  EXPECT_FALSE(bar->isVisible());
  EXPECT_EQ(page->view()->frame(), nullptr);
  EXPECT_EQ(page->state_label()->text(), "–");
}

// A design beyond the paper's: the 3 × 3 example protocol's session through the trial panel,
// on the grasp proxy with the scripted participant. The schedule holds its 36 trials, each of
// the nine conditions ran four times (a practice trial and three blocks), and the
// questionnaire came after each of the last block's nine trials.
TEST(AppSession, RunsASessionOfTheThreeByThreeDesignThroughTheTrialPanel) {
  const QString protocol = QString(HANDLAB_SOURCE_DIR) + "/studies/examples/three-by-three.json";
  const QString db = QString::fromStdString(test::fresh_path("app_3x3.db"));
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ASSERT_EQ(window.create_study(protocol, db), QString());
  enrol_p01(db, 31, 0.191);
  ASSERT_EQ(window.open_study(db), QString());
  window.participants()->select("P01");
  EXPECT_EQ(view_rows(window.participants()->schedule()), 36);

  SessionPage* page = scripted_session(window, studies::WorldKind::kGraspProxy);
  int questionnaires = 0;
  QObject::connect(page, &SessionPage::questionnaire_opened, [&](QuestionnaireForm* dialog) {
    ++questionnaires;
    QTimer::singleShot(0, [dialog] {
      for (int k : {3, 4, 5}) QTest::keyClick(dialog, Qt::Key(Qt::Key_0 + k));
      QTest::keyClick(dialog, Qt::Key_Return);
    });
  });
  QSignalSpy ended(page, &SessionPage::session_ended);
  QTest::mouseClick(page->start_button(), Qt::LeftButton);
  ASSERT_TRUE(page->session_running());
  ASSERT_TRUE(ended.wait(120000)) << "the session ends";
  EXPECT_TRUE(ended.front().front().toString().contains("every trial done"))
      << ended.front().front().toString().toStdString();
  EXPECT_EQ(questionnaires, 9);
  EXPECT_EQ(view_cell(window.participants()->table(), 0, 9), "complete");

  store::StudyStore store(db.toStdString());
  const auto plan = store.plan("P01");
  const auto trials = store.trials("P01");
  ASSERT_EQ(trials.size(), 36u);
  std::map<int, int> runs;  // per condition
  for (const auto& t : trials) ++runs[plan[std::size_t(t.position)].condition];
  ASSERT_EQ(runs.size(), 9u);
  for (const auto& [condition, n] : runs) EXPECT_EQ(n, 4) << "condition " << condition;
  EXPECT_EQ(store.database().query_text("SELECT count(*) FROM answer"), "27");
}

// The mixed example: the form refuses a VR experience in no group and the table shows the
// group; with the participant's window open the questions appear there, full size, answered
// with the keys, while the experimenter's window says answers are awaited; when that window
// closes mid-questionnaire the questions go on in a dialog, the answers given kept.
TEST(AppSession, AMixedDesignGroupsAtEnrolmentAndAsksInTheParticipantsWindow) {
  const QString protocol =
      QString(HANDLAB_SOURCE_DIR) + "/studies/examples/mixed-vr-experience.json";
  const QString db = QString::fromStdString(test::fresh_path("app_mixed.db"));
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ASSERT_EQ(window.create_study(protocol, db), QString());
  when_form_opens([](ParticipantForm* form) {
    QTest::keyClicks(form->id_edit(), "P01");
    form->age_box()->setValue(30);
    form->sex_box()->setCurrentIndex(form->sex_box()->findData("X"));
    form->handedness_box()->setCurrentIndex(form->handedness_box()->findData("right"));
    form->hand_length_box()->setValue(19.0);
    form->vr_box()->setCurrentText("daily");
    EXPECT_TRUE(form->problems().join(" ").contains("in no level of the between factor experience"))
        << form->problems().join(";").toStdString();
    EXPECT_FALSE(form->buttons()->button(QDialogButtonBox::Ok)->isEnabled());
    form->vr_box()->setCurrentText("expert");
    EXPECT_TRUE(form->problems().isEmpty()) << form->problems().join(";").toStdString();
    QTest::mouseClick(form->buttons()->button(QDialogButtonBox::Ok), Qt::LeftButton);
  });
  ASSERT_EQ(window.participants()->add_participant(), "P01");
  QTableView* table = window.participants()->table();
  EXPECT_FALSE(table->isColumnHidden(6));
  EXPECT_EQ(table->model()->headerData(6, Qt::Horizontal).toString(), "Group");
  EXPECT_EQ(view_cell(table, 0, 6), "experienced");

  ParticipantWindow* seen = window.show_participant_window(-1);
  ASSERT_TRUE(QTest::qWaitForWindowExposed(seen));
  SessionPage* page = scripted_session(window, studies::WorldKind::kGraspProxy);
  int questionnaires = 0, in_participant_window = 0;
  QObject::connect(page, &SessionPage::questionnaire_opened, [&](QuestionnaireForm* form) {
    const int n = questionnaires++;
    if (form->window() == seen) {
      ++in_participant_window;
      EXPECT_EQ(seen->questionnaire(), form);
      EXPECT_TRUE(page->state_label()->text().contains("Awaiting the participant's answers"));
    }
    QTimer::singleShot(0, [&, form, n] {
      if (form->window() == seen) {
        EXPECT_GE(form->findChild<QLabel*>()->font().pointSizeF(), 18.0) << "full size";
      }
      if (n == 1) {  // the window closes after one answer: the rest asked over the panel
        QTest::keyClick(form, Qt::Key_2);
        seen->close();
        QApplication::processEvents();
        EXPECT_NE(form->window(), seen);
        EXPECT_TRUE(form->window()->isVisible());
        EXPECT_EQ(form->answers(), (std::vector<int>{2, 0}));
        QTest::keyClick(form, Qt::Key_4);
      } else {
        for (int k : {5, 1}) QTest::keyClick(form, Qt::Key(Qt::Key_0 + k));
      }
      QTest::keyClick(form, Qt::Key_Return);
    });
  });
  QSignalSpy ended(page, &SessionPage::session_ended);
  QTest::mouseClick(page->start_button(), Qt::LeftButton);
  ASSERT_TRUE(page->session_running());
  ASSERT_TRUE(ended.wait(120000)) << "the session ends";
  EXPECT_EQ(questionnaires, 20);  // every trial of every block
  EXPECT_EQ(in_participant_window, 2);

  store::StudyStore store(db.toStdString());
  EXPECT_EQ(store.database().query_text("SELECT count(*) FROM answer"), "40");
  EXPECT_EQ(store.database().query_text(
                "SELECT group_concat(value, ',') FROM (SELECT value FROM answer ORDER BY "
                "trial_id, item LIMIT 4)"),
            "1,5,4,2");  // ease before precision; the second trial's precision 2, ease 4
}

// The trials of a participant, read while another process may be writing (a busy database
// is read again).
std::vector<store::TrialRow> trials_of(const QString& db, const std::string& id) {
  for (int attempt = 0;; ++attempt) {
    try {
      store::StudyStore store(db.toStdString());
      return store.trials(id);
    } catch (const std::exception&) {
      if (attempt == 50) throw;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
}

int count(const std::vector<store::TrialRow>& trials, store::TrialStatus status) {
  return int(std::count_if(trials.begin(), trials.end(),
                           [&](const store::TrialRow& t) { return t.status == status; }));
}

// The app's process killed (SIGKILL) while a trial runs on the soft hand; the study opened
// again in a new window says which session was interrupted and where it resumes; Resume
// takes the experimenter to the session, which goes on at the interrupted trial, and every
// trial finished before the kill is still there.
TEST(AppSession, ResumesInTheAppAfterTheAppWasKilledDuringATrial) {
  const QString db = QString::fromStdString(test::fresh_path("app_killed.db"));
  const studies::Protocol protocol = studies::read_protocol(kProtocol.toStdString());
  store::StudyStore::create(db.toStdString(), studies::study_definition(protocol));
  enrol_p01(db, 35, 0.19);

  // The app runs the session in real time from the command line, as an experimenter would
  // start it, and is killed once two trials are done and the third has run a while.
  QTemporaryDir home;
  QProcess app;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("HOME", home.path());
  app.setProcessEnvironment(env);
  app.setProcessChannelMode(QProcess::ForwardedErrorChannel);
  app.start(HANDLAB_APP, {"--study", db, "--participant", "P01", "--tracker", "scripted", "--world",
                          "soft", "--start"});
  ASSERT_TRUE(app.waitForStarted(10000));
  std::vector<store::TrialRow> trials;
  const bool third_running = QTest::qWaitFor(
      [&] {
        trials = trials_of(db, "P01");
        return trials.size() == 3 && trials[2].status == store::TrialStatus::kRunning;
      },
      180000);
  ASSERT_TRUE(third_running) << trials.size() << " trials";
  QTest::qWait(1500);  // into the trial, its frames being stored
  ASSERT_EQ(app.state(), QProcess::Running);
  app.kill();  // SIGKILL: no handler, no cleanup
  ASSERT_TRUE(app.waitForFinished(10000));
  EXPECT_EQ(app.exitStatus(), QProcess::CrashExit);
  trials = trials_of(db, "P01");
  ASSERT_EQ(trials.size(), 3u);
  EXPECT_EQ(
      count(trials, store::TrialStatus::kCompleted) + count(trials, store::TrialStatus::kTimeout),
      2);
  EXPECT_EQ(trials[2].status, store::TrialStatus::kRunning) << "as the kill left it";
  const int killed_position = trials[2].position;

  // A new window opens the study: the interrupted session is named, with its trial.
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ASSERT_EQ(window.show_study(db), QString());
  window.tabs()->setCurrentWidget(window.home());
  ASSERT_EQ(window.home()->interrupted(), QStringList{"P01"});
  EXPECT_FALSE(window.home()->interrupted_label()->isHidden());
  EXPECT_TRUE(window.home()->interrupted_label()->text().contains(
      QString("resumes at trial %1").arg(killed_position + 1)))
      << window.home()->interrupted_label()->text().toStdString();
  QTest::mouseClick(window.home()->resume_button(), Qt::LeftButton);
  SessionPage* page = window.session();
  ASSERT_EQ(window.tabs()->currentWidget(), page);
  EXPECT_EQ(page->participant_box()->currentText(), "P01");

  // Resumed with the scripted participant on the soft hand, as fast as it goes, until the
  // interrupted trial has run again; then stopped.
  page->tracker_box()->setCurrentIndex(page->tracker_box()->findData(3));
  page->world_box()->setCurrentIndex(
      page->world_box()->findData(int(studies::WorldKind::kSoftHand)));
  page->real_time_box()->setChecked(false);
  QSignalSpy ended(page, &SessionPage::session_ended);
  QTest::mouseClick(page->start_button(), Qt::LeftButton);
  ASSERT_TRUE(page->session_running());
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        trials = trials_of(db, "P01");
        return trials.size() >= 5;  // the killed trial again, then the next one started
      },
      120000));
  page->stop_session();
  ASSERT_TRUE(QTest::qWaitFor([&] { return !ended.isEmpty(); }, 60000));
  EXPECT_TRUE(window.home()->interrupted_label()->isHidden()) << "nothing interrupted now";

  // The record: two trials done before the kill, untouched; the killed one aborted as
  // interrupted; the same position run again in the new session; sessions interrupted, then
  // stopped by the experimenter.
  store::StudyStore store(db.toStdString());
  trials = store.trials("P01");
  ASSERT_GE(trials.size(), 5u);
  EXPECT_EQ(trials[2].position, killed_position);
  EXPECT_EQ(trials[2].status, store::TrialStatus::kAborted);
  EXPECT_EQ(trials[2].reason, "interrupted: the session ended while the trial ran");
  EXPECT_EQ(trials[3].position, killed_position);
  EXPECT_EQ(trials[3].attempt, 2);
  EXPECT_NE(trials[3].session_id, trials[2].session_id);
  EXPECT_TRUE(trials[3].status == store::TrialStatus::kCompleted ||
              trials[3].status == store::TrialStatus::kTimeout);
  EXPECT_EQ(count(trials, store::TrialStatus::kRunning), 0);
  std::vector<std::string> sessions;
  store::Statement s = store.database().prepare("SELECT status FROM session ORDER BY id");
  while (s.step()) sessions.push_back(s.column_text(0));
  EXPECT_EQ(sessions, (std::vector<std::string>{"interrupted", "stopped"}));
}

}  // namespace
}  // namespace handlab::gui

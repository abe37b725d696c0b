// The experimenter's app end to end, through its real widgets: a study created from the
// shipped protocol, a participant added through the form (and a duplicate id refused), the
// session set up, calibrated and run on the soft hand with the scripted participant through
// the trial panel,
// every questionnaire answered in its dialog with the keys, one trial redone with a reason;
// then the study file read back and checked against what was done.
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTableWidget>
#include <QTest>
#include <QTimer>

#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "app/gui/main_window.h"
#include "app/gui/participant_form.h"
#include "app/gui/participants_page.h"
#include "app/gui/questionnaire_dialog.h"
#include "app/gui/session_page.h"
#include "app/gui/session_worker.h"
#include "app/gui/study_home.h"
#include "core/store/study_store.h"
#include "core/util/csv.h"
#include "tests/support/test_files.h"

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

TEST(AppSession, RunsAWholeSessionFromTheWindow) {
  const QString db = QString::fromStdString(test::fresh_path("app_session.db"));
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ASSERT_EQ(window.create_study(kProtocol, db), QString());
  EXPECT_TRUE(window.windowTitle().startsWith("app_session.db"));
  EXPECT_GT(window.home()->summary()->rowCount(), 10) << "the protocol's summary";

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
  ASSERT_EQ(window.participants()->table()->rowCount(), 1);
  EXPECT_EQ(window.participants()->table()->item(0, 4)->text(), "18.4");
  window.participants()->select("P01");
  EXPECT_EQ(window.participants()->schedule()->rowCount(), 24);

  // Set up: the scripted participant on the soft hand, as fast as it goes.
  SessionPage* page = window.session();
  page->participant_box()->setCurrentText("P01");
  page->tracker_box()->setCurrentIndex(3);  // scripted
  page->world_box()->setCurrentIndex(
      page->world_box()->findData(int(studies::WorldKind::kSoftHand)));
  page->real_time_box()->setChecked(false);
  std::vector<std::vector<int>> answered;
  int questionnaires = 0;
  QObject::connect(page, &SessionPage::questionnaire_opened, [&](QuestionnaireDialog* dialog) {
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
  // With `page` as the context the slot runs on the window's thread, as a click would.
  QObject::connect(page->worker(), &SessionWorker::trial_ended, page,
                   [&](int position, bool, double, bool) {
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
  EXPECT_EQ(window.participants()->table()->item(0, 8)->text(), "complete");

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
  ASSERT_EQ(window.export_table(csv, false), QString());
  const auto rows = util::parse_csv(test::file_bytes(csv.toStdString()));
  EXPECT_EQ(rows.size(), 1u + 20u) << "header and the 20 block trials";
  ASSERT_EQ(window.open_data_table(csv), QString());
  auto* table = window.findChild<QTableWidget*>("data_table");
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->rowCount(), 20);
}

}  // namespace
}  // namespace handlab::gui

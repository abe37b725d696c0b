#include "app/gui/participants_page.h"

#include <map>

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include "app/gui/participant_form.h"
#include "app/gui/trial_status_text.h"
#include "core/store/study_store.h"
#include "core/util/csv.h"
#include "studies/export/study_export.h"
#include "studies/session/enrolment.h"
#include "studies/session/session_runner.h"

namespace handlab::gui {
namespace {

QTableWidgetItem* cell(const QString& text) {
  auto* item = new QTableWidgetItem(text);
  item->setFlags(item->flags() & ~Qt::ItemIsEditable);
  return item;
}

}  // namespace

ParticipantsPage::ParticipantsPage(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* buttons = new QHBoxLayout;
  add_ = new QPushButton(tr("Add Participant… (Ctrl+Shift+A)"));
  add_->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_A));
  edit_ = new QPushButton(tr("Edit…"));
  buttons->addWidget(add_);
  buttons->addWidget(edit_);
  buttons->addStretch();
  layout->addLayout(buttons);
  connect(add_, &QPushButton::clicked, this, [this] { add_participant(); });
  connect(edit_, &QPushButton::clicked, this, [this] { edit_participant(); });

  auto* split = new QSplitter(Qt::Vertical);
  table_ = new QTableWidget(0, 10);
  table_->setObjectName("participants");
  table_->setHorizontalHeaderLabels({tr("Id"), tr("Age"), tr("Sex"), tr("Handedness"),
                                     tr("Hand length (cm)"), tr("VR experience"), tr("Group"),
                                     tr("Notes"), tr("Trials done / planned"), tr("Status")});
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);
  table_->verticalHeader()->hide();
  table_->horizontalHeader()->setStretchLastSection(true);
  connect(table_, &QTableWidget::itemSelectionChanged, this, &ParticipantsPage::show_schedule);
  connect(table_, &QTableWidget::cellDoubleClicked, this, [this] { edit_participant(); });
  split->addWidget(table_);

  auto* lower = new QWidget;
  auto* lower_layout = new QVBoxLayout(lower);
  lower_layout->setContentsMargins(0, 0, 0, 0);
  schedule_title_ = new QLabel(tr("Select a participant to see their schedule."));
  auto* schedule_head = new QHBoxLayout;
  schedule_head->addWidget(schedule_title_, 1);
  replay_ = new QPushButton(tr("Replay Trial"));
  replay_->setToolTip(tr("Play the selected trial back from its frame log (or double-click it)"));
  replay_->setEnabled(false);
  schedule_head->addWidget(replay_);
  lower_layout->addLayout(schedule_head);
  schedule_ = new QTableWidget(0, 8);
  schedule_->setObjectName("schedule");
  schedule_->setHorizontalHeaderLabels({tr("Trial"), tr("Block"), tr("Order"), tr("Condition"),
                                        tr("Repetition"), tr("Questionnaire"), tr("Status"),
                                        tr("Result")});
  schedule_->verticalHeader()->hide();
  schedule_->horizontalHeader()->setStretchLastSection(true);
  schedule_->setSelectionBehavior(QAbstractItemView::SelectRows);
  schedule_->setSelectionMode(QAbstractItemView::SingleSelection);
  schedule_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  lower_layout->addWidget(schedule_);
  // A trial that ran (its status is not "planned") can be played back.
  auto ran = [this](int row) {
    return row >= 0 && schedule_->item(row, 6) && schedule_->item(row, 6)->text() != tr("planned");
  };
  connect(schedule_, &QTableWidget::itemSelectionChanged, this,
          [this, ran] { replay_->setEnabled(ran(schedule_->currentRow())); });
  auto request = [this, ran](int row) {
    if (ran(row)) emit replay_requested(selected(), schedule_->item(row, 0)->text().toInt() - 1);
  };
  connect(replay_, &QPushButton::clicked, this,
          [this, request] { request(schedule_->currentRow()); });
  connect(schedule_, &QTableWidget::cellDoubleClicked, this,
          [request](int row, int) { request(row); });
  split->addWidget(lower);
  layout->addWidget(split);
  set_study({});
}

void ParticipantsPage::set_study(const QString& database) {
  database_ = database;
  add_->setEnabled(!database.isEmpty());
  edit_->setEnabled(!database.isEmpty());
  refresh();
}

QString ParticipantsPage::selected() const {
  const int row = table_->currentRow();
  return row >= 0 && table_->item(row, 0) ? table_->item(row, 0)->text() : QString();
}

void ParticipantsPage::select(const QString& id) {
  for (int r = 0; r < table_->rowCount(); ++r)
    if (table_->item(r, 0)->text() == id) table_->selectRow(r);
}

QStringList ParticipantsPage::ids() const {
  QStringList ids;
  for (int r = 0; r < table_->rowCount(); ++r) ids << table_->item(r, 0)->text();
  return ids;
}

void ParticipantsPage::refresh(const QString& select_id) {
  const QString keep = select_id.isEmpty() ? selected() : select_id;
  table_->setRowCount(0);
  QStringList enrolled;
  bool grouped = false;  // the protocol has between-participants factors
  if (!database_.isEmpty()) {
    store::StudyStore store(database_.toStdString());
    std::map<std::string, studies::ParticipantStatus> status;
    for (auto& s : studies::study_status(store)) status[s.id] = s;
    for (const store::Participant& p : store.participants()) {
      const int row = table_->rowCount();
      table_->insertRow(row);
      const studies::ParticipantStatus& s = status[p.id];
      const int done = s.trials_completed + s.trials_skipped;
      const QString id = QString::fromStdString(p.id);
      enrolled << id;
      const QString state =
          id == in_session_ ? tr("in session")
          : store.has_running_session(p.id)
              ? tr("interrupted: resume at trial %1").arg(s.next ? s.next->position + 1 : 0)
          : done == 0 ? tr("not started")
          : done < s.trials_planned
              ? tr("in progress (next: trial %1)").arg(s.next ? s.next->position + 1 : 0)
              : tr("complete");
      table_->setItem(row, 0, cell(id));
      if (p.simulated) table_->item(row, 0)->setToolTip(tr("simulated participant"));
      table_->setItem(row, 1, cell(QString::number(p.age)));
      table_->setItem(row, 2, cell(QString::fromStdString(p.sex)));
      table_->setItem(row, 3, cell(QString::fromStdString(p.handedness)));
      table_->setItem(row, 4, cell(QString::number(p.hand_length * 100.0, 'f', 1)));
      table_->setItem(row, 5, cell(QString::fromStdString(p.vr_experience)));
      QStringList group;  // "vr novice" for each between factor of the protocol
      for (const auto& [factor, level] : p.between_levels)
        group << QString::fromStdString(p.between_levels.size() > 1 ? factor + " " + level : level);
      grouped = grouped || !group.isEmpty();
      table_->setItem(row, 6, cell(group.join(", ")));
      table_->setItem(row, 7, cell(QString::fromStdString(p.notes)));
      table_->setItem(row, 8, cell(QString("%1 / %2").arg(done).arg(s.trials_planned)));
      table_->setItem(row, 9, cell(state));
    }
  }
  table_->setColumnHidden(6, !grouped);
  table_->resizeColumnsToContents();
  if (!keep.isEmpty())
    select(keep);
  else if (table_->rowCount() > 0)
    table_->selectRow(0);
  show_schedule();
  emit participants_changed(enrolled, selected());
}

void ParticipantsPage::show_schedule() {
  schedule_->setRowCount(0);
  replay_->setEnabled(false);
  const QString id = selected();
  if (database_.isEmpty() || id.isEmpty()) {
    schedule_title_->setText(tr("Select a participant to see their schedule."));
    return;
  }
  store::StudyStore store(database_.toStdString());
  const store::StudyInfo info = store.study();
  const auto plan = store.plan(id.toStdString());
  // The newest attempt of each planned trial.
  std::map<int, store::TrialRow> last;
  for (const store::TrialRow& t : store.trials(id.toStdString())) last[t.position] = t;
  schedule_title_->setText(tr("Schedule of %1: %2 trials").arg(id).arg(plan.size()));
  for (const store::PlannedTrialRow& r : plan) {
    const int row = schedule_->rowCount();
    schedule_->insertRow(row);
    schedule_->setItem(row, 0, cell(QString::number(r.position + 1)));
    schedule_->setItem(row, 1, cell(r.practice ? tr("practice") : QString::number(r.block)));
    schedule_->setItem(row, 2, cell(QString::number(r.order)));
    schedule_->setItem(
        row, 3, cell(QString::fromStdString(info.conditions.at(std::size_t(r.condition)).first)));
    schedule_->setItem(row, 4, cell(QString::number(r.repetition)));
    schedule_->setItem(row, 5, cell(r.questionnaire ? tr("yes") : QString()));
    const auto found = last.find(r.position);
    QString status = tr("planned"), result;
    if (found != last.end()) {
      const store::TrialRow& t = found->second;
      status = trial_status_text(t.status);
      if (t.attempt > 1) status += tr(" (attempt %1)").arg(t.attempt);
      if (t.status == store::TrialStatus::kCompleted || t.status == store::TrialStatus::kTimeout)
        result = tr("%1 s, %2 %3, %4 %5")
                     .arg(QString::fromStdString(
                         util::format_number(std::round(t.completion_time_s * 1000.0) / 1000.0)))
                     .arg(t.grasps)
                     .arg(t.grasps == 1 ? tr("grasp") : tr("grasps"))
                     .arg(t.drops)
                     .arg(t.drops == 1 ? tr("drop") : tr("drops"));
      else if (!t.reason.empty())
        result = QString::fromStdString(t.reason);
    }
    schedule_->setItem(row, 6, cell(status));
    schedule_->setItem(row, 7, cell(result));
    if (r.practice)
      for (int c = 0; c < schedule_->columnCount(); ++c)
        schedule_->item(row, c)->setBackground(QColor(240, 240, 232));
  }
  schedule_->resizeColumnsToContents();
}

QString ParticipantsPage::add_participant() {
  if (database_.isEmpty()) return {};
  store::StudyStore store(database_.toStdString());
  const studies::Protocol protocol = studies::stored_protocol(store);
  ParticipantForm form(store.participants(), nullptr, this, &protocol);
  if (form.exec() != QDialog::Accepted) return {};
  const store::Participant p = form.participant();
  try {
    studies::enrol_participant(store, p);
  } catch (const std::exception& e) {
    QMessageBox::warning(this, tr("Add Participant"), QString::fromStdString(e.what()));
    return {};
  }
  const QString id = QString::fromStdString(p.id);
  refresh(id);
  return id;
}

QString ParticipantsPage::edit_participant() {
  const QString id = selected();
  if (database_.isEmpty() || id.isEmpty()) return {};
  store::StudyStore store(database_.toStdString());
  const auto current = store.participant(id.toStdString());
  if (!current) return {};
  const studies::Protocol protocol = studies::stored_protocol(store);
  ParticipantForm form(store.participants(), &*current, this, &protocol);
  if (form.exec() != QDialog::Accepted) return {};
  try {
    store::Participant changed = form.participant();
    changed.simulated = current->simulated;
    studies::update_participant(store, changed);
  } catch (const std::exception& e) {
    QMessageBox::warning(this, tr("Edit Participant"), QString::fromStdString(e.what()));
    return {};
  }
  refresh();
  return id;
}

}  // namespace handlab::gui

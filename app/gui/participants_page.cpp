#include "app/gui/participants_page.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QSplitter>
#include <QTableView>
#include <QVBoxLayout>

#include "app/gui/participant_form.h"
#include "app/gui/study_tables.h"
#include "app/gui/text_table_model.h"
#include "studies/protocol/protocol_store.h"
#include "studies/session/enrolment.h"

namespace handlab::gui {
namespace {

QTableView* table_view(TextTableModel* model, const char* name) {
  auto* view = new QTableView;
  view->setObjectName(name);
  view->setModel(model);
  view->setSelectionBehavior(QAbstractItemView::SelectRows);
  view->setSelectionMode(QAbstractItemView::SingleSelection);
  view->setEditTriggers(QAbstractItemView::NoEditTriggers);
  view->verticalHeader()->hide();
  view->horizontalHeader()->setStretchLastSection(true);
  return view;
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
  participants_ = new TextTableModel(StudyTables::participant_headers(), this);
  table_ = table_view(participants_, "participants");
  connect(table_->selectionModel(), &QItemSelectionModel::selectionChanged, this,
          &ParticipantsPage::show_schedule);
  connect(table_, &QTableView::doubleClicked, this, [this] { edit_participant(); });
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
  trials_ = new TextTableModel(StudyTables::schedule_headers(), this);
  schedule_ = table_view(trials_, "schedule");
  lower_layout->addWidget(schedule_);
  connect(schedule_->selectionModel(), &QItemSelectionModel::currentRowChanged, this,
          [this](const QModelIndex& current) { replay_->setEnabled(trial_ran(current.row())); });
  auto request = [this](int row) {
    if (trial_ran(row)) emit replay_requested(selected(), trials_->text(row, 0).toInt() - 1);
  };
  connect(replay_, &QPushButton::clicked, this,
          [this, request] { request(schedule_->currentIndex().row()); });
  connect(schedule_, &QTableView::doubleClicked, this,
          [request](const QModelIndex& index) { request(index.row()); });
  split->addWidget(lower);
  layout->addWidget(split);
  set_study(OpenStudy{});
}

void ParticipantsPage::set_study(OpenStudy study) {
  study_ = std::move(study);
  add_->setEnabled(study_.is_open());
  edit_->setEnabled(study_.is_open());
  refresh();
}

int ParticipantsPage::selected_row() const {
  const QModelIndexList rows = table_->selectionModel()->selectedRows();
  return rows.isEmpty() ? -1 : rows.front().row();
}

QString ParticipantsPage::selected() const {
  return participants_->text(selected_row(), 0);
}

void ParticipantsPage::select(const QString& id) {
  if (const int row = participants_->find(0, id); row >= 0) table_->selectRow(row);
}

QStringList ParticipantsPage::ids() const {
  QStringList ids;
  for (int r = 0; r < participants_->rowCount(); ++r) ids << participants_->text(r, 0);
  return ids;
}

bool ParticipantsPage::trial_ran(int row) const {
  return row >= 0 && row < trials_->rowCount() &&
         trials_->text(row, StudyTables::kScheduleStatusColumn) != StudyTables::tr("planned");
}

void ParticipantsPage::refresh(const QString& select_id) {
  const QString keep = select_id.isEmpty() ? selected() : select_id;
  participants_->set_rows(study_.is_open() ? StudyTables::participants(*study_.store, in_session_)
                                           : std::vector<TextRow>{});
  bool grouped = false;  // the protocol has between-participants factors
  for (int r = 0; r < participants_->rowCount(); ++r)
    grouped = grouped || !participants_->text(r, StudyTables::kGroupColumn).isEmpty();
  table_->setColumnHidden(StudyTables::kGroupColumn, !grouped);
  table_->resizeColumnsToContents();
  if (!keep.isEmpty()) select(keep);
  if (selected_row() < 0 && participants_->rowCount() > 0) table_->selectRow(0);
  // A row selected after the reset has shown its schedule (selectionChanged); none: clear it.
  if (selected_row() < 0) show_schedule();
  emit participants_changed(ids(), selected());
}

void ParticipantsPage::show_schedule() {
  replay_->setEnabled(false);
  const QString id = selected();
  if (!study_.is_open() || id.isEmpty()) {
    trials_->set_rows({});
    schedule_title_->setText(tr("Select a participant to see their schedule."));
    return;
  }
  trials_->set_rows(StudyTables::schedule(*study_.store, id));
  schedule_title_->setText(tr("Schedule of %1: %2 trials").arg(id).arg(trials_->rowCount()));
  schedule_->resizeColumnsToContents();
}

QString ParticipantsPage::add_participant() {
  if (!study_.is_open()) return {};
  const auto open = study_.store;  // held through the form's event loop
  store::StudyStore& store = *open;
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
  if (!study_.is_open() || id.isEmpty()) return {};
  const auto open = study_.store;  // held through the form's event loop
  store::StudyStore& store = *open;
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

#include "app/gui/study_home.h"

#include <QFileInfo>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QTableView>
#include <QVBoxLayout>

#include "app/gui/text_table_model.h"
#include "core/store/study_store.h"
#include "studies/export/study_export.h"
#include "studies/protocol/protocol_store.h"
#include "studies/session/enrolment.h"

namespace handlab::gui {

StudyHome::StudyHome(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  title_ = new QLabel;
  title_->setObjectName("home_title");
  title_->setStyleSheet("QLabel { font-size: 16pt; font-weight: bold; }");
  layout->addWidget(title_);

  none_ = new QWidget;
  auto* none = new QVBoxLayout(none_);
  auto* create = new QPushButton(tr("New Study from a Protocol… (Ctrl+N)"));
  auto* open = new QPushButton(tr("Open Study… (Ctrl+O)"));
  connect(create, &QPushButton::clicked, this, &StudyHome::new_study_requested);
  connect(open, &QPushButton::clicked, this, &StudyHome::open_study_requested);
  none->addWidget(create);
  none->addWidget(open);
  none->addWidget(new QLabel(tr("Recent studies (double-click to open):")));
  recent_ = new QListWidget;
  recent_->setObjectName("recent");
  connect(recent_, &QListWidget::itemActivated, this,
          [this](QListWidgetItem* item) { emit open_recent_requested(item->toolTip()); });
  none->addWidget(recent_);
  layout->addWidget(none_);

  open_ = new QWidget;
  auto* opened = new QVBoxLayout(open_);
  opened->setContentsMargins(0, 0, 0, 0);
  interrupted_label_ = new QLabel;
  interrupted_label_->setObjectName("interrupted");
  interrupted_label_->setWordWrap(true);
  interrupted_label_->setStyleSheet(
      "QLabel { background: #fff4d6; border: 1px solid #d9a300; padding: 8px; }");
  resume_ = new QPushButton;
  resume_->setObjectName("resume");
  connect(resume_, &QPushButton::clicked, this, [this] {
    if (!interrupted_.isEmpty()) emit resume_requested(interrupted_.front());
  });
  opened->addWidget(interrupted_label_);
  opened->addWidget(resume_);
  summary_rows_ = new TextTableModel({tr("Item"), tr("Value")}, this);
  summary_ = new QTableView;
  summary_->setObjectName("study_summary");
  summary_->setModel(summary_rows_);
  summary_->horizontalHeader()->hide();
  summary_->verticalHeader()->hide();
  summary_->horizontalHeader()->setStretchLastSection(true);
  summary_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  summary_->setWordWrap(true);
  opened->addWidget(summary_);
  layout->addWidget(open_);
  set_study(OpenStudy{});
}

void StudyHome::set_recent(const QStringList& files) {
  recent_->clear();
  for (const QString& f : files) {
    auto* item =
        new QListWidgetItem(QFileInfo(f).fileName() + "  —  " + QFileInfo(f).absolutePath());
    item->setToolTip(f);
    recent_->addItem(item);
  }
}

void StudyHome::set_study(OpenStudy study, const QString& own_session) {
  study_ = std::move(study);
  interrupted_.clear();
  none_->setVisible(!study_.is_open());
  open_->setVisible(study_.is_open());
  if (!study_.is_open()) {
    title_->setText(tr("No study open"));
    summary_rows_->set_rows({});
    return;
  }
  store::StudyStore& store = *study_.store;
  const store::StudyInfo info = store.study();
  title_->setText(tr("Study %1 — %2")
                      .arg(QString::fromStdString(info.name), QFileInfo(study_.path).fileName()));
  std::vector<TextRow> rows;
  auto add = [&](const QString& label, const QString& value) {
    rows.push_back({{label, value}, {}, {}});
  };
  add(tr("File"), study_.path);
  add(tr("Created"), QString::fromStdString(info.created_at));
  for (const auto& [label, value] : studies::protocol_summary(studies::stored_protocol(store)))
    add(QString::fromStdString(label), QString::fromStdString(value));
  const auto status = studies::study_status(store);
  int done = 0, planned = 0;
  QStringList lines;
  for (const auto& s : status) {
    done += s.trials_completed + s.trials_skipped;
    planned += s.trials_planned;
    if (QString::fromStdString(s.id) != own_session && store.has_running_session(s.id)) {
      interrupted_ << QString::fromStdString(s.id);
      lines << tr("%1: a session was interrupted; it resumes at trial %2 (the interrupted trial "
                  "is kept as aborted and runs again).")
                   .arg(QString::fromStdString(s.id))
                   .arg(s.next ? s.next->position + 1 : 0);
    }
  }
  add(tr("Participants"),
      tr("%1 enrolled, %2 of %3 trials done").arg(status.size()).arg(done).arg(planned));
  const store::StudyCompleteness completeness = store.completeness();
  if (completeness.partial())
    add(tr("Partial study"),
        tr("%1: merged from only some of its parts; merge the rest in (handlab-cli merge "
           "--update) before reading its results as the study's")
            .arg(QString::fromStdString(completeness.describe())));
  summary_rows_->set_rows(std::move(rows));
  summary_->resizeColumnToContents(0);
  summary_->resizeRowsToContents();
  interrupted_label_->setVisible(!interrupted_.isEmpty());
  resume_->setVisible(!interrupted_.isEmpty());
  interrupted_label_->setText(lines.join("\n"));
  if (!interrupted_.isEmpty())
    resume_->setText(tr("Resume %1's Session…").arg(interrupted_.front()));
}

}  // namespace handlab::gui

#include "app/gui/study_panel.h"

#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "core/store/study_store.h"
#include "studies/export/study_export.h"

namespace handlab::gui {

StudyPanel::StudyPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  title_ = new QLabel(tr("No study open"), this);
  title_->setWordWrap(true);
  table_ = new QTableWidget(0, 6, this);
  table_->setHorizontalHeaderLabels({tr("Participant"), tr("Planned"), tr("Completed"),
                                     tr("Skipped"), tr("Aborted"), tr("Next")});
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->verticalHeader()->hide();
  setMinimumWidth(520);  // every column readable without scrolling
  auto* refresh = new QPushButton(tr("&Refresh"), this);
  connect(refresh, &QPushButton::clicked, this, &StudyPanel::refresh);
  layout->addWidget(title_);
  layout->addWidget(table_);
  layout->addWidget(refresh);
}

QString StudyPanel::open_database(const QString& path) {
  path_ = path;
  refresh();
  return table_->isEnabled() ? QString() : title_->text();
}

void StudyPanel::refresh() {
  if (path_.isEmpty()) return;
  try {
    store::StudyStore store(path_.toStdString());
    const store::StudyInfo info = store.study();
    const auto status = studies::study_status(store);
    title_->setText(tr("<b>%1</b> — %2 participants, %3 conditions<br><small>%4</small>")
                        .arg(QString::fromStdString(info.name))
                        .arg(status.size())
                        .arg(info.conditions.size())
                        .arg(path_.toHtmlEscaped()));
    table_->setRowCount(int(status.size()));
    for (int r = 0; r < int(status.size()); ++r) {
      const auto& p = status[std::size_t(r)];
      const QString next =
          p.next ? tr("%1: %2 (%3)")
                       .arg(p.next->position + 1)
                       .arg(QString::fromStdString(p.next_condition))
                       .arg(p.next->practice ? tr("practice") : tr("block %1").arg(p.next->block))
                 : tr("done");
      const QStringList cells = {
          QString::fromStdString(p.id),        QString::number(p.trials_planned),
          QString::number(p.trials_completed), QString::number(p.trials_skipped),
          QString::number(p.trials_aborted),   next};
      for (int c = 0; c < cells.size(); ++c) table_->setItem(r, c, new QTableWidgetItem(cells[c]));
    }
    table_->setEnabled(true);
  } catch (const std::exception& e) {
    table_->setRowCount(0);
    table_->setEnabled(false);
    title_->setText(QString::fromStdString(e.what()));
  }
}

}  // namespace handlab::gui

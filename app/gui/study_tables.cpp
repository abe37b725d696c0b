#include "app/gui/study_tables.h"

#include <cmath>
#include <map>

#include "app/gui/trial_status_text.h"
#include "core/util/csv.h"
#include "studies/export/study_export.h"

namespace handlab::gui {
namespace {

QString text(const std::string& s) {
  return QString::fromStdString(s);
}

}  // namespace

QStringList StudyTables::participant_headers() {
  return {tr("Id"),
          tr("Age"),
          tr("Sex"),
          tr("Handedness"),
          tr("Hand length (cm)"),
          tr("VR experience"),
          tr("Group"),
          tr("Notes"),
          tr("Trials done / planned"),
          tr("Status")};
}

QStringList StudyTables::schedule_headers() {
  return {tr("Trial"),      tr("Block"),         tr("Order"),  tr("Condition"),
          tr("Repetition"), tr("Questionnaire"), tr("Status"), tr("Result")};
}

std::vector<TextRow> StudyTables::participants(store::StudyStore& store,
                                               const QString& in_session) {
  std::map<std::string, studies::ParticipantStatus> status;
  for (auto& s : studies::study_status(store)) status[s.id] = s;
  std::vector<TextRow> rows;
  for (const store::Participant& p : store.participants()) {
    const studies::ParticipantStatus& s = status[p.id];
    const int done = s.trials_completed + s.trials_skipped;
    const QString id = text(p.id);
    const int next = s.next ? s.next->position + 1 : 0;
    const QString state = id == in_session ? tr("in session")
                          : store.has_running_session(p.id)
                              ? tr("interrupted: resume at trial %1").arg(next)
                          : done == 0               ? tr("not started")
                          : done < s.trials_planned ? tr("in progress (next: trial %1)").arg(next)
                                                    : tr("complete");
    QStringList group;  // "vr novice" for each between factor of the protocol
    for (const auto& [factor, level] : p.between_levels)
      group << text(p.between_levels.size() > 1 ? factor + " " + level : level);
    TextRow row;
    row.cells = {id,
                 QString::number(p.age),
                 text(p.sex),
                 text(p.handedness),
                 QString::number(p.hand_length * 100.0, 'f', 1),
                 text(p.vr_experience),
                 group.join(", "),
                 text(p.notes),
                 QString("%1 / %2").arg(done).arg(s.trials_planned),
                 state};
    if (p.simulated) row.tooltip = tr("simulated participant");
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<TextRow> StudyTables::schedule(store::StudyStore& store, const QString& participant) {
  const store::StudyInfo info = store.study();
  const std::string id = participant.toStdString();
  // The newest attempt of each planned trial.
  std::map<int, store::TrialRow> last;
  for (const store::TrialRow& t : store.trials(id)) last[t.position] = t;
  std::vector<TextRow> rows;
  for (const store::PlannedTrialRow& r : store.plan(id)) {
    QString status = tr("planned"), result;
    if (const auto found = last.find(r.position); found != last.end()) {
      const store::TrialRow& t = found->second;
      status = trial_status_text(t.status);
      if (t.attempt > 1) status += tr(" (attempt %1)").arg(t.attempt);
      if (t.status == store::TrialStatus::kCompleted || t.status == store::TrialStatus::kTimeout)
        result =
            tr("%1 s, %2 %3, %4 %5")
                .arg(text(util::format_number(std::round(t.completion_time_s * 1000.0) / 1000.0)))
                .arg(t.grasps)
                .arg(t.grasps == 1 ? tr("grasp") : tr("grasps"))
                .arg(t.drops)
                .arg(t.drops == 1 ? tr("drop") : tr("drops"));
      else if (!t.reason.empty())
        result = text(t.reason);
    }
    TextRow row;
    row.cells = {QString::number(r.position + 1),
                 r.practice ? tr("practice") : QString::number(r.block),
                 QString::number(r.order),
                 text(info.conditions.at(std::size_t(r.condition)).first),
                 QString::number(r.repetition),
                 r.questionnaire ? tr("yes") : QString(),
                 status,
                 result};
    if (r.practice) row.background = QColor(240, 240, 232);
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace handlab::gui

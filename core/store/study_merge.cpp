#include "core/store/study_merge.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "core/store/study_schema.h"
#include "core/store/study_store.h"
#include "core/util/sha256.h"
#include "core/util/temporary_files.h"

namespace handlab::store {
namespace {

using IdMap = std::map<std::int64_t, std::int64_t>;

// A participant's rows of each table, selected by its id (?1), ordered as stored. The first
// column is the row's own id (0 where nothing refers to it), the others are inserted as they
// are but for the foreign keys that `remap` names (a column and the table it refers to).
struct TableCopy {
  const char* select;
  const char* insert;
  std::vector<std::pair<int, const char*>> remap;
  const char* name;  // the map its ids go into (nullptr: none)
};

const std::vector<TableCopy>& participant_tables() {
  static const std::vector<TableCopy> tables = {
      {"SELECT id, participant_id, position, block, order_in_block, condition_id, repetition, "
       "practice, questionnaire FROM planned_trial WHERE participant_id = ?1 ORDER BY position",
       "INSERT INTO planned_trial (participant_id, position, block, order_in_block, "
       "condition_id, repetition, practice, questionnaire) VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
       {},
       "planned_trial"},
      {"SELECT 0, participant_id, model, model_sha256, seed, parameters FROM simulated_person "
       "WHERE participant_id = ?1",
       "INSERT INTO simulated_person (participant_id, model, model_sha256, seed, parameters) "
       "VALUES (?, ?, ?, ?, ?)",
       {},
       nullptr},
      {"SELECT id, participant_id, tracker, started_at, ended_at, status FROM session "
       "WHERE participant_id = ?1 ORDER BY id",
       "INSERT INTO session (participant_id, tracker, started_at, ended_at, status) "
       "VALUES (?, ?, ?, ?, ?)",
       {},
       "session"},
      {"SELECT t.id, t.planned_id, t.session_id, t.attempt, t.status, t.started_at, t.ended_at, "
       "t.completion_time_s, t.grasps, t.drops, t.reason, t.frames FROM trial t "
       "JOIN planned_trial p ON p.id = t.planned_id WHERE p.participant_id = ?1 ORDER BY t.id",
       "INSERT INTO trial (planned_id, session_id, attempt, status, started_at, ended_at, "
       "completion_time_s, grasps, drops, reason, frames) "
       "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
       {{1, "planned_trial"}, {2, "session"}},
       "trial"},
      {"SELECT e.id, e.trial_id, e.t, e.kind FROM event e JOIN trial t ON t.id = e.trial_id "
       "JOIN planned_trial p ON p.id = t.planned_id WHERE p.participant_id = ?1 ORDER BY e.id",
       "INSERT INTO event (trial_id, t, kind) VALUES (?, ?, ?)",
       {{1, "trial"}},
       nullptr},
      {"SELECT 0, a.trial_id, a.item, a.value FROM answer a JOIN trial t ON t.id = a.trial_id "
       "JOIN planned_trial p ON p.id = t.planned_id WHERE p.participant_id = ?1 "
       "ORDER BY a.rowid",
       "INSERT INTO answer (trial_id, item, value) VALUES (?, ?, ?)",
       {{1, "trial"}},
       nullptr},
      {"SELECT f.id, f.trial_id, f.seq, f.t, f.data FROM frame f JOIN trial t ON t.id = "
       "f.trial_id JOIN planned_trial p ON p.id = t.planned_id WHERE p.participant_id = ?1 "
       "ORDER BY f.id",
       "INSERT INTO frame (trial_id, seq, t, data) VALUES (?, ?, ?, ?)",
       {{1, "trial"}},
       nullptr},
      {"SELECT 0, m.trial_id, m.memory FROM simulated_memory m JOIN trial t ON t.id = "
       "m.trial_id JOIN planned_trial p ON p.id = t.planned_id WHERE p.participant_id = ?1 "
       "ORDER BY m.trial_id",
       "INSERT INTO simulated_memory (trial_id, memory) VALUES (?, ?)",
       {{1, "trial"}},
       nullptr},
  };
  return tables;
}

constexpr const char* kStoredParticipantColumns =
    "id, age, sex, handedness, hand_length, vr_experience, notes, created_at, simulated, "
    "between_levels";

// Everything stored of a participant but the ids the rows happen to have and its place in the
// enrolment order, as one digest: equal digests, the same data.
std::string participant_digest(Database& db, const std::string& id) {
  std::string text;
  auto add_rows = [&](const std::string& sql, const std::set<int>& skipped) {
    Statement s = db.prepare(sql);
    s.bind(1, id);
    while (s.step()) {
      for (int c = 0; c < s.column_count(); ++c) {
        if (skipped.count(c)) continue;
        text += char('0' + s.column_type(c));  // 1 (integer) and '1' (text) differ
        if (!s.is_null(c)) {
          const std::vector<std::uint8_t> bytes = s.column_blob(c);  // any type, as stored
          text += util::sha256_hex(
              std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
        }
        text += '\x1f';
      }
      text += '\x1e';
    }
    text += '\x1d';
  };
  add_rows(std::string("SELECT ") + kStoredParticipantColumns + " FROM participant WHERE id = ?1",
           {});
  // The rows without their ids; the foreign keys as the referred row's place among the
  // participant's own rows.
  for (const TableCopy& table : participant_tables()) {
    std::set<int> ids = {0};
    for (const auto& r : table.remap) ids.insert(r.first);
    add_rows(table.select, ids);
  }
  add_rows(
      "SELECT p.position, (SELECT count(*) FROM session s WHERE s.participant_id = ?1 AND "
      "s.id <= t.session_id) FROM trial t JOIN planned_trial p ON p.id = t.planned_id "
      "WHERE p.participant_id = ?1 ORDER BY t.id",
      {});
  for (const char* table : {"event", "answer", "frame", "simulated_memory"})
    add_rows(std::string("SELECT (SELECT count(*) FROM trial u JOIN planned_trial q ON q.id = "
                         "u.planned_id WHERE q.participant_id = ?1 AND u.id <= x.trial_id) "
                         "FROM ") +
                 table +
                 " x JOIN trial t ON t.id = x.trial_id JOIN planned_trial p ON p.id = "
                 "t.planned_id WHERE p.participant_id = ?1 ORDER BY x.rowid",
             {});
  return util::sha256_hex(text);
}

// The id a referred row took in the merged study; a reference to a row that is not the
// participant's own (a damaged part) is refused by the part's name.
std::int64_t mapped_id(const IdMap& map, std::int64_t id, const Database& from,
                       const char* referred) {
  const auto it = map.find(id);
  if (it == map.end())
    throw StoreError(from.path() + ": a row refers to " + referred + " " + std::to_string(id) +
                     ", which is not its participant's");
  return it->second;
}

void copy_participant(Database& from, Database& to, const std::string& id, int enrolment) {
  {
    Statement s = from.prepare(std::string("SELECT ") + kStoredParticipantColumns +
                               " FROM participant WHERE id = ?");
    s.bind(1, id);
    if (!s.step()) throw StoreError(from.path() + " has no participant " + id);
    Statement insert =
        to.prepare(std::string("INSERT INTO participant (") + kStoredParticipantColumns +
                   ", enrolment) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    for (int c = 0; c < 10; ++c) insert.bind_column(c + 1, s, c);
    insert.bind(11, std::int64_t(enrolment)).run();
  }
  std::map<std::string, IdMap> maps;
  for (const TableCopy& table : participant_tables()) {
    Statement s = from.prepare(table.select);
    s.bind(1, id);
    Statement insert = to.prepare(table.insert);
    while (s.step()) {
      for (int c = 1; c < s.column_count(); ++c) {
        const auto remapped = std::find_if(table.remap.begin(), table.remap.end(),
                                           [&](const auto& r) { return r.first == c; });
        if (remapped == table.remap.end())
          insert.bind_column(c, s, c);
        else
          insert.bind(c,
                      mapped_id(maps[remapped->second], s.column_int64(c), from, remapped->second));
      }
      insert.run();
      if (table.name) maps[table.name][s.column_int64(0)] = to.last_insert_rowid();
    }
  }
}

StudyDefinition definition_of(const StudyInfo& info) {
  return {info.name,    info.protocol_text, info.seed,
          info.factors, info.conditions,    info.planned_participants};
}

// A part opened read-only, after checking that it is an intact handlab study.
std::unique_ptr<StudyStore> open_part(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw StoreError(path + ": no such file");
  refuse_unfinished_file(path);
  checked_study_file(path);  // says what the file is when it is no study
  std::string integrity;
  try {
    Database db(path, Database::Mode::kQueryOnly);
    integrity = db.query_text("PRAGMA integrity_check").value_or("");
  } catch (const StoreError&) {
    integrity = "unreadable";
  }
  if (integrity != "ok")
    throw StoreError(
        path + " is damaged (cut short or overwritten; SQLite's integrity check: " + integrity +
        "): copy the part again from where it was made, or run its task again");
  try {
    return std::make_unique<StudyStore>(path, StudyStore::Access::kReadOnly);
  } catch (const StoreError& e) {
    throw StoreError(path + " is not a handlab study: " + e.what());
  }
}

// The population seeds a part's simulated people were drawn with (none for people): parts
// of one simulated study share one.
std::set<std::uint64_t> population_seeds(Database& db) {
  std::set<std::uint64_t> seeds;
  Statement s = db.prepare("SELECT DISTINCT seed FROM simulated_person");
  while (s.step()) seeds.insert(std::uint64_t(s.column_int64(0)));
  return seeds;
}

std::string seeds_text(const std::set<std::uint64_t>& seeds) {
  if (seeds.empty()) return "no simulated people";
  std::string text = seeds.size() == 1 ? "population seed" : "population seeds";
  for (std::uint64_t seed : seeds) text += " " + std::to_string(seed);
  return text;
}

void remove_database(const std::string& path) {
  std::error_code ignored;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"})
    std::filesystem::remove(path + suffix, ignored);
}

}  // namespace

MergeResult merge_studies(const std::vector<std::string>& named_parts, const std::string& out,
                          const MergeOptions& options) {
  std::error_code ec;
  if (named_parts.empty()) throw StoreError("merge: name the parts to merge");
  std::vector<std::string> parts = named_parts;
  if (std::filesystem::exists(out, ec)) {
    if (!options.update) throw StoreError(out + " exists: a merge writes a new study");
    const StudyCompleteness before = open_part(out)->completeness();
    // Whole by its plan: nothing to add. A study without a plan (of people) is merged again.
    if (before.planned > 0 && !before.partial()) {
      MergeResult whole;
      whole.whole_already = true;
      whole.participants = before.planned;
      return whole;
    }
    parts.insert(parts.begin(), out);  // what it holds is merged again with the new parts
  }
  std::vector<std::unique_ptr<StudyStore>> stores;
  for (const std::string& path : parts) stores.push_back(open_part(path));
  const StudyInfo first = stores.front()->study();
  const std::set<std::uint64_t> first_seeds = population_seeds(stores.front()->database());
  std::string created_at = first.created_at;  // the merged study's: its earliest part's
  // Each participant's part and place; a second copy only if its data are the same.
  struct Member {
    std::size_t part;
    int enrolment;
    std::string id;
  };
  std::vector<Member> members;
  std::map<std::string, std::size_t> member_of;  // id -> index in members
  MergeResult result;
  for (std::size_t k = 0; k < stores.size(); ++k) {
    const StudyInfo info = stores[k]->study();
    const std::string& sha = info.protocol_sha256;
    created_at = std::min(created_at, info.created_at);
    if (sha != first.protocol_sha256)
      throw StoreError(parts[k] + " is a study of another protocol (sha256 " + sha.substr(0, 12) +
                       "…; " + parts.front() + " has " + first.protocol_sha256.substr(0, 12) +
                       "…)");
    const std::set<std::uint64_t> seeds = population_seeds(stores[k]->database());
    if (info.planned_participants != first.planned_participants || seeds != first_seeds)
      throw StoreError(parts[k] + " is a part of another study (" +
                       std::to_string(info.planned_participants) + " planned participants, " +
                       seeds_text(seeds) + "; " + parts.front() + " has " +
                       std::to_string(first.planned_participants) + ", " +
                       seeds_text(first_seeds) + ")");
    for (const Participant& p : stores[k]->participants()) {
      const auto seen = member_of.find(p.id);
      if (seen == member_of.end()) {
        member_of[p.id] = members.size();
        members.push_back({k, p.enrolment, p.id});
        continue;
      }
      const Member& m = members[seen->second];
      if (participant_digest(stores[m.part]->database(), p.id) !=
          participant_digest(stores[k]->database(), p.id))
        throw StoreError("participant " + p.id + " is in " + parts[m.part] + " and " + parts[k] +
                         " with different data");
      ++result.duplicates;
    }
  }
  std::set<int> places;
  for (const Member& m : members) places.insert(m.enrolment);
  result.renumbered = places.size() != members.size();
  if (result.renumbered)
    std::stable_sort(members.begin(), members.end(), [](const Member& a, const Member& b) {
      return a.part != b.part ? a.part < b.part : a.enrolment < b.enrolment;
    });
  else
    std::sort(members.begin(), members.end(),
              [](const Member& a, const Member& b) { return a.enrolment < b.enrolment; });

  StudyCompleteness completeness;
  completeness.planned = first.planned_participants;
  for (int place = 0; place < completeness.planned; ++place)
    if (!places.count(place)) completeness.missing_places.push_back(place);
  if (completeness.partial() && !options.partial)
    throw StoreError("the parts hold " + completeness.describe() +
                     ": merge every part, or give --partial to write a study that says it is "
                     "partial until the rest are merged in (merge --update)");

  const std::string partial = out + ".partial";
  remove_database(partial);
  // Removed if the merge fails or is stopped (Ctrl-C, scancel): no stray file, and nothing
  // under the output's name that looks like a study.
  util::TemporaryDatabase unfinished(partial);
  StudyStore::create(partial, definition_of(first));
  {
    StudyStore merged(partial, StudyStore::Access::kUnfinished);
    Database& db = merged.database();
    Transaction t(db);
    db.prepare("UPDATE study SET created_at = ?").bind(1, created_at).run();
    for (std::size_t i = 0; i < members.size(); ++i) {
      const Member& m = members[i];
      copy_participant(stores[m.part]->database(), db, m.id,
                       result.renumbered ? int(i) : m.enrolment);
    }
    t.commit();
    db.exec("PRAGMA journal_mode = DELETE");  // one file, as the study is handed on
  }
  std::filesystem::rename(partial, out, ec);
  if (ec) throw StoreError("merge: cannot rename " + partial + " to " + out + ": " + ec.message());
  unfinished.keep();
  result.participants = int(members.size());
  result.completeness = completeness;
  return result;
}

}  // namespace handlab::store

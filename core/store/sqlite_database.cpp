#include "core/store/sqlite_database.h"

#include <filesystem>

#include <sqlite3.h>

namespace handlab::store {
namespace {

// What a failure of SQLite means to the person whose file it is, for the failures a file
// can cause; empty for the others (a program error), which keep SQLite's words.
std::string what_happened(int code, const std::string& file) {
  switch (code & 0xff) {
    case SQLITE_CORRUPT:
      return file +
             " is damaged: it is not a whole SQLite database (cut short, or overwritten "
             "in part); restore it from a copy";
    case SQLITE_NOTADB:
      return file + " is not a study database (not an SQLite file)";
    case SQLITE_FULL:
      return "the disk holding " + file + " is full: free some space and run again";
    case SQLITE_READONLY:
      return file + " cannot be written: it, or its folder, is read-only";
    case SQLITE_CANTOPEN:
      return file + " cannot be opened: it or its folder is missing, or not readable";
    case SQLITE_PERM:
    case SQLITE_AUTH:
      return "no permission to use " + file;
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return file + " is locked by another program writing it: try again when it is done";
    case SQLITE_IOERR:
      return file + " could not be read or written (an input/output error of its disk)";
    default:
      return {};
  }
}

std::string failure_message(sqlite3* db, int code, const std::string& what,
                            const std::string& file) {
  const std::string sqlite = db ? sqlite3_errmsg(db) : sqlite3_errstr(code);
  const std::string plain = what_happened(code, file.empty() ? "the study database" : file);
  if (!plain.empty()) return plain + " (SQLite: " + sqlite + ")";
  return what + ": " + sqlite + (file.empty() ? std::string() : " (" + file + ")");
}

[[noreturn]] void fail(sqlite3* db, const std::string& what) {
  const char* file = db ? sqlite3_db_filename(db, "main") : nullptr;
  throw StoreError(failure_message(db, db ? sqlite3_extended_errcode(db) : SQLITE_NOMEM, what,
                                   file ? file : ""));
}

}  // namespace

Statement::Statement(sqlite3* db, std::string_view sql) : db_(db) {
  if (sqlite3_prepare_v2(db, sql.data(), int(sql.size()), &stmt_, nullptr) != SQLITE_OK)
    fail(db, "cannot prepare \"" + std::string(sql.substr(0, 60)) + "\"");
}

Statement::~Statement() {
  sqlite3_finalize(stmt_);
}

Statement::Statement(Statement&& other) noexcept : db_(other.db_), stmt_(other.stmt_) {
  other.stmt_ = nullptr;
}

Statement& Statement::bind(int index, std::int64_t value) {
  if (sqlite3_bind_int64(stmt_, index, value) != SQLITE_OK) fail(db_, "bind");
  return *this;
}
Statement& Statement::bind(int index, double value) {
  if (sqlite3_bind_double(stmt_, index, value) != SQLITE_OK) fail(db_, "bind");
  return *this;
}
Statement& Statement::bind(int index, std::string_view text) {
  if (sqlite3_bind_text(stmt_, index, text.data(), int(text.size()), SQLITE_TRANSIENT) != SQLITE_OK)
    fail(db_, "bind");
  return *this;
}
Statement& Statement::bind_blob(int index, std::span<const std::uint8_t> bytes) {
  if (sqlite3_bind_blob(stmt_, index, bytes.data(), int(bytes.size()), SQLITE_TRANSIENT) !=
      SQLITE_OK)
    fail(db_, "bind");
  return *this;
}
Statement& Statement::bind_null(int index) {
  if (sqlite3_bind_null(stmt_, index) != SQLITE_OK) fail(db_, "bind");
  return *this;
}

Statement& Statement::bind_column(int index, const Statement& source, int column) {
  if (sqlite3_bind_value(stmt_, index, sqlite3_column_value(source.stmt_, column)) != SQLITE_OK)
    fail(db_, "bind");
  return *this;
}

int Statement::column_count() const {
  return sqlite3_column_count(stmt_);
}

bool Statement::step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  fail(db_, "step");
}

void Statement::run() {
  while (step()) {
  }
  reset();
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

bool Statement::is_null(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}
int Statement::column_type(int column) const {
  return sqlite3_column_type(stmt_, column);
}
std::int64_t Statement::column_int64(int column) const {
  return sqlite3_column_int64(stmt_, column);
}
double Statement::column_double(int column) const {
  return sqlite3_column_double(stmt_, column);
}
std::string Statement::column_text(int column) const {
  const auto* text = sqlite3_column_text(stmt_, column);
  return text ? std::string(reinterpret_cast<const char*>(text),
                            std::size_t(sqlite3_column_bytes(stmt_, column)))
              : std::string();
}
std::vector<std::uint8_t> Statement::column_blob(int column) const {
  const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(stmt_, column));
  return data ? std::vector<std::uint8_t>(data, data + sqlite3_column_bytes(stmt_, column))
              : std::vector<std::uint8_t>();
}

namespace {

sqlite3* open_connection(const std::string& path, const std::string& shown, int flags) {
  sqlite3* db = nullptr;
  const int code = sqlite3_open_v2(path.c_str(), &db, flags, nullptr);
  if (code != SQLITE_OK) {
    const std::string message = failure_message(db, code, "cannot open " + shown, shown);
    sqlite3_close(db);
    throw StoreError(message);
  }
  return db;
}

// The whole of the file at `path` into `memory`, read through a read-only connection.
void copy_into(sqlite3* memory, const std::string& path) {
  sqlite3* source = open_connection(path, path, SQLITE_OPEN_READWRITE);
  sqlite3_busy_timeout(source, 2000);
  sqlite3_exec(source, "PRAGMA query_only = ON", nullptr, nullptr, nullptr);
  sqlite3_backup* backup = sqlite3_backup_init(memory, "main", source, "main");
  int done = backup ? sqlite3_backup_step(backup, -1) : sqlite3_errcode(memory);
  for (int tries = 0; (done == SQLITE_BUSY || done == SQLITE_LOCKED) && tries < 20; ++tries) {
    sqlite3_sleep(100);  // a writer holds the file: the backup starts again when it is done
    done = sqlite3_backup_step(backup, -1);
  }
  sqlite3_backup_finish(backup);
  const std::string message = failure_message(nullptr, done, "cannot read " + path, path);
  sqlite3_close(source);
  if (done != SQLITE_DONE) throw StoreError(message);
}

}  // namespace

Database::Database(const std::string& path, Mode mode) : path_(path) {
  int flags = SQLITE_OPEN_READONLY;
  if (mode == Mode::kReadWrite || mode == Mode::kInspect || mode == Mode::kQueryOnly)
    flags = SQLITE_OPEN_READWRITE;
  if (mode == Mode::kReadWriteCreate || mode == Mode::kMemoryCopy)
    flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  db_ = open_connection(mode == Mode::kMemoryCopy ? ":memory:" : path, path, flags);
  if (mode == Mode::kMemoryCopy) {
    try {
      copy_into(db_, path);
    } catch (...) {
      sqlite3_close(db_);
      throw;
    }
  }
  sqlite3_extended_result_codes(db_, 1);
  sqlite3_busy_timeout(db_, 2000);
  try {
    exec("PRAGMA foreign_keys = ON");
    if (mode == Mode::kQueryOnly) exec("PRAGMA query_only = ON");
    if (mode == Mode::kReadWrite || mode == Mode::kReadWriteCreate) {
      const auto journal = query_text("PRAGMA journal_mode = WAL");
      if (!journal || *journal != "wal") throw StoreError("cannot switch " + path + " to WAL mode");
      exec("PRAGMA synchronous = NORMAL");
    }
  } catch (...) {
    sqlite3_close(db_);
    throw;
  }
}

int Database::last_error_code() const {
  return sqlite3_errcode(db_);
}

Database::~Database() {
  sqlite3_close(db_);
}

void Database::exec(std::string_view sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, std::string(sql).c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const int code = sqlite3_extended_errcode(db_);
    const std::string plain = what_happened(code, path_);
    const std::string message =
        plain.empty() ? std::string(error ? error : sqlite3_errmsg(db_)) + " (" + path_ + ")"
                      : plain + " (SQLite: " + (error ? error : sqlite3_errmsg(db_)) + ")";
    sqlite3_free(error);
    throw StoreError(message);
  }
}

Statement Database::prepare(std::string_view sql) {
  return Statement(db_, sql);
}

std::optional<std::string> Database::query_text(std::string_view sql) {
  Statement statement = prepare(sql);
  if (!statement.step()) return std::nullopt;
  return statement.column_text(0);
}

std::int64_t Database::last_insert_rowid() const {
  return sqlite3_last_insert_rowid(db_);
}

int Database::changes() const {
  return sqlite3_changes(db_);
}

Transaction::Transaction(Database& db) : db_(db) {
  db_.exec("BEGIN IMMEDIATE");
}

Transaction::~Transaction() {
  if (!done_) {
    try {
      db_.exec("ROLLBACK");
    } catch (...) {  // the connection is already rolled back when a statement failed hard
    }
  }
}

void Transaction::commit() {
  db_.exec("COMMIT");
  done_ = true;
}

void remove_database_files(const std::string& path) {
  std::error_code ignored;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"})
    std::filesystem::remove(path + suffix, ignored);
}

}  // namespace handlab::store

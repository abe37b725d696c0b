// A thin RAII layer over the SQLite C API: a connection, prepared statements, transactions.
// Every failure throws StoreError with SQLite's message and the file it concerns.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace handlab::store {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Statement {
 public:
  Statement(sqlite3* db, std::string_view sql);
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&&) = delete;
  Statement(const Statement&) = delete;

  // Parameters are 1-based, as in SQL's ?NNN.
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, double value);
  Statement& bind(int index, std::string_view text);
  Statement& bind_blob(int index, std::span<const std::uint8_t> bytes);
  Statement& bind_null(int index);
  // The value in `source`'s current row at `column`, with its type (a copy between databases).
  Statement& bind_column(int index, const Statement& source, int column);

  // Advances; true while a row is available.
  bool step();
  // Runs a statement that returns no rows.
  void run();
  void reset();

  bool is_null(int column) const;
  // SQLite's storage class of the value: SQLITE_INTEGER, _FLOAT, _TEXT, _BLOB or _NULL (1-5).
  int column_type(int column) const;
  std::int64_t column_int64(int column) const;
  double column_double(int column) const;
  std::string column_text(int column) const;
  std::vector<std::uint8_t> column_blob(int column) const;
  int column_count() const;

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

class Database {
 public:
  // kInspect: read-write but nothing set (the journal mode left as the file has it), to look
  // at a file before claiming it. SQLite's read-only connections to a WAL database that
  // other processes are writing can fail with I/O errors; a read-write one reads safely.
  // kQueryOnly: as kInspect, with every change refused (PRAGMA query_only): a reader that
  // cannot write, safe beside writers as kReadOnly is not. kMemoryCopy: a writable database
  // in memory holding a copy of the file (SQLite's backup, read through a query-only
  // connection), to read a file as if changed (an older schema migrated) without writing it.
  enum class Mode { kReadWriteCreate, kReadWrite, kReadOnly, kInspect, kQueryOnly, kMemoryCopy };

  // Opens with foreign keys on and, for kReadWrite(Create), write-ahead logging.
  explicit Database(const std::string& path, Mode mode = Mode::kReadWriteCreate);
  // The primary result code of the last call that failed (SQLITE_NOTADB, ...).
  int last_error_code() const;
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  void exec(std::string_view sql);
  Statement prepare(std::string_view sql);
  std::optional<std::string> query_text(std::string_view sql);  // first column of the first row
  std::int64_t last_insert_rowid() const;
  int changes() const;  // rows changed by the last INSERT, UPDATE or DELETE
  const std::string& path() const { return path_; }
  sqlite3* handle() { return db_; }

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

// BEGIN IMMEDIATE on construction; ROLLBACK on destruction unless commit() was called.
class Transaction {
 public:
  explicit Transaction(Database& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

// Deletes a closed database file and SQLite's files beside it (-wal, -shm, -journal); files
// that are not there are no error.
void remove_database_files(const std::string& path);

}  // namespace handlab::store

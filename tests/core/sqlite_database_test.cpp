#include <filesystem>

#include <gtest/gtest.h>

#include "core/store/sqlite_database.h"

namespace handlab::store {
namespace {

std::string fresh_path(const std::string& name) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/" + name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path + suffix);
  return path;
}

TEST(SqliteDatabase, WalTransactionReopenReadBack) {
  const std::string path = fresh_path("smoke.sqlite");
  {
    Database db(path);
    EXPECT_EQ(db.query_text("PRAGMA journal_mode"), "wal");
    EXPECT_EQ(db.query_text("PRAGMA foreign_keys"), "1");
    db.exec(
        "CREATE TABLE trial (id INTEGER PRIMARY KEY, condition TEXT NOT NULL, time REAL, frame "
        "BLOB)");
    Transaction tx(db);
    Statement insert = db.prepare("INSERT INTO trial (condition, time, frame) VALUES (?1, ?2, ?3)");
    const std::vector<std::uint8_t> blob = {0, 1, 2, 255};
    for (int i = 0; i < 100; ++i) {
      insert.bind(1, i % 2 ? "Fine Ours" : "Gross Naive").bind(2, 1.5 + i).bind_blob(3, blob);
      insert.run();
    }
    tx.commit();
  }
  Database db(path, Database::Mode::kReadOnly);
  Statement q = db.prepare("SELECT count(*), sum(time), max(condition) FROM trial");
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.column_int64(0), 100);
  EXPECT_DOUBLE_EQ(q.column_double(1), 100 * 1.5 + 4950.0);
  EXPECT_EQ(q.column_text(2), "Gross Naive");
  Statement b = db.prepare("SELECT frame FROM trial LIMIT 1");
  ASSERT_TRUE(b.step());
  EXPECT_EQ(b.column_blob(0), (std::vector<std::uint8_t>{0, 1, 2, 255}));
}

TEST(SqliteDatabase, UncommittedTransactionRollsBack) {
  const std::string path = fresh_path("rollback.sqlite");
  Database db(path);
  db.exec("CREATE TABLE t (x INTEGER)");
  {
    Transaction tx(db);
    db.exec("INSERT INTO t VALUES (1)");
  }
  EXPECT_EQ(db.query_text("SELECT count(*) FROM t"), "0");
}

TEST(SqliteDatabase, ForeignKeysAreEnforced) {
  Database db(fresh_path("fk.sqlite"));
  db.exec("CREATE TABLE p (id TEXT PRIMARY KEY); CREATE TABLE c (pid TEXT REFERENCES p(id))");
  EXPECT_THROW(db.exec("INSERT INTO c VALUES ('nobody')"), StoreError);
}

TEST(SqliteDatabase, ErrorsNameTheFile) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/no/such/dir/x.sqlite";
  try {
    Database db(path);
    FAIL() << "opening in a missing directory must fail";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace handlab::store

// The study a window has open: its file, and its store opened once by the window and handed to
// its pages, which read and write it on the UI thread. Work on a thread of its own (a session,
// an analysis) opens its own connection from the path: a connection is not shared between
// threads.
#pragma once

#include <memory>

#include <QString>

#include "core/store/study_store.h"

namespace handlab::gui {

struct OpenStudy {
  QString path;  // absolute
  std::shared_ptr<store::StudyStore> store;

  bool is_open() const { return store != nullptr; }
};

}  // namespace handlab::gui

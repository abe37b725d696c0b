// The live path measured in the app (docs/performance.md): once the session's first trial
// has run for a warm-up, the session page's display figures are taken over a stated time,
// the session is stopped (the trial kept as aborted) and the figures written as JSON.
#pragma once

#include <QObject>
#include <QString>

namespace handlab::gui {

class SessionPage;

class LiveMeasurement : public QObject {
  Q_OBJECT

 public:
  LiveMeasurement(SessionPage* page, double seconds, QString json_path, QObject* parent = nullptr);

 signals:
  void done(bool written);

 private:
  void begin();
  void finish();

  SessionPage* page_;
  double seconds_;
  QString json_path_;
  bool started_ = false, taken_ = false;
  QString figures_;
};

}  // namespace handlab::gui

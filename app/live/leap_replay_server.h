// A recording served as the Leap service serves its device: the WebSocket JSON protocol
// (v6 at /v6.json; the greeting, a device event, then every frame at the recording's own
// pace to every client, looped with ids and timestamps that keep increasing). For running a
// session with no device at hand, and for measuring the live path (docs/performance.md).
#pragma once

#include <chrono>
#include <vector>

#include <QObject>
#include <QTimer>
#include <QWebSocketServer>

#include "core/tracking/tracked_frame.h"

class QWebSocket;

namespace handlab::live {

struct LeapReplayOptions {
  quint16 port = 6437;  // 0: any free port
  bool loop = true;
};

class LeapReplayServer : public QObject {
  Q_OBJECT

 public:
  // At least two frames with increasing timestamps (a read recording has them).
  LeapReplayServer(std::vector<tracking::TrackedFrame> frames, LeapReplayOptions options = {},
                   QObject* parent = nullptr);
  ~LeapReplayServer() override;

  // Starts listening on loopback and the recording's clock; false with `error` set.
  bool start(QString* error);
  quint16 port() const { return server_.serverPort(); }
  long frames_sent() const { return frames_sent_; }
  double frame_rate_hz() const { return rate_hz_; }

 signals:
  void finished();  // without looping, after the last frame

 private:
  void send_due();

  std::vector<tracking::TrackedFrame> frames_;
  LeapReplayOptions options_;
  QWebSocketServer server_;
  QTimer timer_;
  std::vector<QWebSocket*> clients_;
  std::chrono::steady_clock::time_point start_;
  double period_s_ = 0;  // the recording's length plus one mean frame interval
  double rate_hz_ = 0;
  long next_ = 0;  // frames served so far, counting the loops
  long frames_sent_ = 0;
};

}  // namespace handlab::live

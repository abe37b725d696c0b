// The live Leap Motion stream: the Leap service's WebSocket JSON protocol (also served for
// Ultraleap devices by Ultraleap's WebSocket bridge). Connects to ws://HOST:6437/v6.json,
// reads the {"version", "serviceVersion"} greeting, sends the "background" and "focused"
// options, steps down a protocol version when the server closes with 1001, reconnects with
// exponential backoff, and reports device and hand-lost state. Its socket and timer are its
// children, so it can live on a thread of its own (moveToThread), where a busy window does
// not delay the frames.
#pragma once

#include <QObject>
#include <QTimer>
#include <QUrl>
#include <QWebSocket>

#include "app/live/frame_queue.h"
#include "core/tracking/tracked_frame.h"

namespace handlab::live {

struct LeapClientOptions {
  QUrl server = QUrl("ws://127.0.0.1:6437");
  int protocol_version = 6;
  bool background = true;  // receive frames while the app is not focused
  int first_backoff_ms = 250;
  int max_backoff_ms = 8000;
  double hand_lost_after_s = 0.25;  // no hand in frames for this long: hand lost
};

class LeapWebSocketClient : public QObject {
  Q_OBJECT

 public:
  explicit LeapWebSocketClient(LeapClientOptions options = {}, QObject* parent = nullptr);
  ~LeapWebSocketClient() override;

  void start();
  void stop();

  bool connected() const { return connected_; }
  int protocol_version() const { return version_; }
  QString service_version() const { return service_version_; }
  bool device_streaming() const { return device_streaming_; }
  bool hand_visible() const { return hand_visible_; }
  int frames_received() const { return frames_received_; }
  int messages_rejected() const { return messages_rejected_; }
  // Frames also go here, for a session runner on another thread.
  FrameQueue& queue() { return queue_; }

 signals:
  void connection_changed(bool connected);
  void device_changed(bool attached, bool streaming);
  void hand_visibility_changed(bool visible);
  void frame_received(const handlab::tracking::TrackedFrame& frame);
  void message_rejected(const QString& reason);

 private:
  void open_socket();
  void on_connected();
  void on_disconnected();
  void on_message(const QString& text);
  void schedule_reconnect();

  LeapClientOptions options_;
  QWebSocket socket_;       // a child: it moves with the client
  QTimer reconnect_timer_;  // a child
  FrameQueue queue_;
  int version_;
  int backoff_ms_;
  bool running_ = false, connected_ = false, greeted_ = false;
  bool device_streaming_ = false, hand_visible_ = false;
  double last_hand_time_ = -1.0;
  QString service_version_;
  int frames_received_ = 0, messages_rejected_ = 0;
};

}  // namespace handlab::live

#include "app/live/leap_websocket_client.h"

#include <algorithm>

#include "core/tracking/leap_json.h"
#include "core/util/json_value.h"

namespace handlab::live {

LeapWebSocketClient::LeapWebSocketClient(LeapClientOptions options, QObject* parent)
    : QObject(parent),
      options_(std::move(options)),
      socket_(QString(), QWebSocketProtocol::VersionLatest, this),
      reconnect_timer_(this),
      version_(options_.protocol_version),
      backoff_ms_(options_.first_backoff_ms) {
  reconnect_timer_.setSingleShot(true);
  connect(&reconnect_timer_, &QTimer::timeout, this, &LeapWebSocketClient::open_socket);
  connect(&socket_, &QWebSocket::connected, this, &LeapWebSocketClient::on_connected);
  connect(&socket_, &QWebSocket::disconnected, this, &LeapWebSocketClient::on_disconnected);
  connect(&socket_, &QWebSocket::textMessageReceived, this, &LeapWebSocketClient::on_message);
}

LeapWebSocketClient::~LeapWebSocketClient() {
  stop();
}

void LeapWebSocketClient::start() {
  running_ = true;
  open_socket();
}

void LeapWebSocketClient::stop() {
  running_ = false;
  reconnect_timer_.stop();
  socket_.abort();
  queue_.close();
}

void LeapWebSocketClient::open_socket() {
  if (!running_) return;
  QUrl url = options_.server;
  url.setPath(QString("/v%1.json").arg(version_));
  greeted_ = false;
  socket_.open(url);
}

void LeapWebSocketClient::on_connected() {
  connected_ = true;
  backoff_ms_ = options_.first_backoff_ms;
  // The options LeapJS sends: frames in the background, and this client as the focused one.
  socket_.sendTextMessage(
      QString(R"({"background": %1})").arg(options_.background ? "true" : "false"));
  socket_.sendTextMessage(R"({"focused": true})");
  emit connection_changed(true);
}

void LeapWebSocketClient::on_disconnected() {
  const bool was_connected = connected_;
  connected_ = false;
  if (was_connected) emit connection_changed(false);
  if (hand_visible_) {
    hand_visible_ = false;
    emit hand_visibility_changed(false);
  }
  if (!running_) return;
  // A service that does not speak this version closes with 1001 before greeting: ask for
  // the previous one at once.
  if (socket_.closeCode() == QWebSocketProtocol::CloseCodeGoingAway && !greeted_ && version_ > 1) {
    --version_;
    reconnect_timer_.start(0);
    return;
  }
  schedule_reconnect();
}

void LeapWebSocketClient::schedule_reconnect() {
  reconnect_timer_.start(backoff_ms_);
  backoff_ms_ = std::min(2 * backoff_ms_, options_.max_backoff_ms);
}

void LeapWebSocketClient::on_message(const QString& text) {
  const std::string utf8 = text.toStdString();
  util::JsonValue message;
  try {
    message = util::JsonValue::parse(utf8);
  } catch (const util::JsonError& e) {
    ++messages_rejected_;
    emit message_rejected(QString::fromStdString(e.what()));
    return;
  }
  if (const auto* version = message.find("version"); version && message.find("serviceVersion")) {
    greeted_ = true;
    if (version->is_number()) version_ = int(version->as_number());
    service_version_ = QString::fromStdString(
        message["serviceVersion"].is_string() ? message["serviceVersion"].as_string() : "");
    return;
  }
  if (const auto* event = message.find("event")) {
    // {"event": {"type": "deviceEvent", "state": {"attached": true, "streaming": true, ...}}}
    if (const auto* state = event->find("state")) {
      const auto* attached = state->find("attached");
      const auto* streaming = state->find("streaming");
      const bool is_attached = attached && attached->is_bool() && attached->as_bool();
      device_streaming_ = streaming && streaming->is_bool() && streaming->as_bool();
      emit device_changed(is_attached, device_streaming_);
    }
    return;
  }
  std::string error;
  auto frame = tracking::parse_leap_frame(message, &error);
  if (!frame) {
    ++messages_rejected_;
    emit message_rejected(QString::fromStdString(error));
    return;
  }
  ++frames_received_;
  device_streaming_ = true;
  if (!frame->hands.empty()) {
    last_hand_time_ = frame->timestamp;
    if (!hand_visible_) {
      hand_visible_ = true;
      emit hand_visibility_changed(true);
    }
  } else if (hand_visible_ && frame->timestamp - last_hand_time_ > options_.hand_lost_after_s) {
    hand_visible_ = false;
    emit hand_visibility_changed(false);
  }
  queue_.push(*frame);
  emit frame_received(*frame);
}

}  // namespace handlab::live

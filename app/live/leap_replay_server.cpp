#include "app/live/leap_replay_server.h"

#include <cmath>
#include <stdexcept>

#include <QWebSocket>

#include "core/tracking/leap_json.h"

namespace handlab::live {

LeapReplayServer::LeapReplayServer(std::vector<tracking::TrackedFrame> frames,
                                   LeapReplayOptions options, QObject* parent)
    : QObject(parent),
      frames_(std::move(frames)),
      options_(options),
      server_("handlab Leap replay", QWebSocketServer::NonSecureMode, this),
      timer_(this) {
  if (frames_.size() < 2 || !(frames_.back().timestamp > frames_.front().timestamp))
    throw std::invalid_argument("a replay needs two frames or more, in time order");
  const double length = frames_.back().timestamp - frames_.front().timestamp;
  rate_hz_ = double(frames_.size() - 1) / length;
  period_s_ = length + 1.0 / rate_hz_;
  timer_.setSingleShot(true);
  timer_.setTimerType(Qt::PreciseTimer);
  connect(&timer_, &QTimer::timeout, this, &LeapReplayServer::send_due);
  connect(&server_, &QWebSocketServer::newConnection, this, [this] {
    while (QWebSocket* socket = server_.nextPendingConnection()) {
      if (socket->requestUrl().path() != "/v6.json") {  // the one version served
        socket->close(QWebSocketProtocol::CloseCodeGoingAway);
        socket->deleteLater();
        continue;
      }
      clients_.push_back(socket);
      connect(socket, &QWebSocket::disconnected, this, [this, socket] {
        std::erase(clients_, socket);
        socket->deleteLater();
      });
      socket->sendTextMessage(R"({"serviceVersion":"handlab replay","version":6})");
      socket->sendTextMessage(
          R"({"event":{"type":"deviceEvent","state":{"attached":true,"streaming":true,"type":"peripheral"}}})");
    }
  });
}

LeapReplayServer::~LeapReplayServer() {
  for (QWebSocket* socket : clients_) socket->abort();
}

bool LeapReplayServer::start(QString* error) {
  if (!server_.listen(QHostAddress::LocalHost, options_.port)) {
    if (error) *error = server_.errorString();
    return false;
  }
  start_ = std::chrono::steady_clock::now();
  next_ = 0;
  send_due();
  return true;
}

void LeapReplayServer::send_due() {
  const long n = long(frames_.size());
  const double t0 = frames_.front().timestamp;
  auto due = [&](long k) {  // seconds after the start
    return double(k / n) * period_s_ + frames_[std::size_t(k % n)].timestamp - t0;
  };
  const double now =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  while ((options_.loop || next_ < n) && due(next_) <= now) {
    tracking::TrackedFrame frame = frames_[std::size_t(next_ % n)];
    const long loop = next_ / n;
    frame.timestamp += double(loop) * period_s_;
    frame.id += loop * (frames_.back().id - frames_.front().id + 1);
    const QString message = QString::fromStdString(tracking::leap_message(frame, rate_hz_));
    for (QWebSocket* socket : clients_) socket->sendTextMessage(message);
    ++frames_sent_;
    ++next_;
  }
  if (!options_.loop && next_ >= n) {
    emit finished();
    return;
  }
  const double wait_ms = std::max(0.0, (due(next_) - now) * 1e3);
  timer_.start(std::chrono::milliseconds(long(std::ceil(wait_ms))));
}

}  // namespace handlab::live

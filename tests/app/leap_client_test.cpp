// The live client against a real WebSocket server on loopback that behaves like the Leap
// service: greeting, options, then frames of a real recording.
#include <QTest>
#include <QWebSocket>
#include <QWebSocketServer>

#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>

#include <gtest/gtest.h>

#include "app/live/leap_replay_server.h"
#include "app/live/leap_websocket_client.h"
#include "core/tracking/lz_string.h"
#include "core/tracking/recording_io.h"
#include "core/util/json_value.h"

namespace handlab::live {
namespace {

std::vector<std::string> recording_messages() {
  std::ifstream in(std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz");
  std::stringstream text;
  text << in.rdbuf();
  const auto doc = util::JsonValue::parse(tracking::lz_decompress_base64(text.str()));
  std::vector<std::string> messages;
  for (const auto& frame : doc["frames"].as_array()) messages.push_back(frame.dump());
  return messages;
}

// Serves frames [first, last) of the recording to each client, as the Leap service would.
class FakeLeapService : public QObject {
 public:
  FakeLeapService(quint16 port, std::vector<std::string> messages, std::size_t first,
                  std::size_t last, bool refuse_v6 = false)
      : server_("fake leap", QWebSocketServer::NonSecureMode),
        messages_(std::move(messages)),
        first_(first),
        last_(last),
        refuse_v6_(refuse_v6) {
    EXPECT_TRUE(server_.listen(QHostAddress::LocalHost, port))
        << server_.errorString().toStdString();
    connect(&server_, &QWebSocketServer::newConnection, this, [this] {
      QWebSocket* socket = server_.nextPendingConnection();
      paths.push_back(socket->requestUrl().path());
      if (refuse_v6_ && socket->requestUrl().path() == "/v6.json") {
        socket->close(QWebSocketProtocol::CloseCodeGoingAway);
        return;
      }
      connect(socket, &QWebSocket::textMessageReceived, this,
              [this](const QString& m) { options.push_back(m); });
      sockets_.emplace_back(socket);
      socket->sendTextMessage(R"({"serviceVersion":"2.3.1+33747","version":6})");
      socket->sendTextMessage(
          R"({"event":{"type":"deviceEvent","state":{"attached":true,"streaming":true,"type":"peripheral"}}})");
      for (std::size_t i = first_; i < last_; ++i)
        socket->sendTextMessage(QString::fromStdString(messages_[i]));
    });
  }
  quint16 port() const { return server_.serverPort(); }
  void shut_down() {
    for (auto& s : sockets_) s->close();
    sockets_.clear();
    server_.close();
  }

  std::vector<QString> options, paths;

 private:
  QWebSocketServer server_;
  std::vector<std::string> messages_;
  std::size_t first_, last_;
  bool refuse_v6_;
  std::vector<std::unique_ptr<QWebSocket>> sockets_;
};

TEST(LeapWebSocketClient, ReceivesEveryFrameInOrderAndSurvivesARestart) {
  const auto messages = recording_messages();
  ASSERT_EQ(messages.size(), 307u);
  auto service = std::make_unique<FakeLeapService>(0, messages, 0, 150);
  const quint16 port = service->port();

  LeapClientOptions options;
  options.server = QUrl(QString("ws://127.0.0.1:%1").arg(port));
  options.first_backoff_ms = 50;
  LeapWebSocketClient client(options);
  std::vector<std::int64_t> ids;
  bool device = false;
  QObject::connect(&client, &LeapWebSocketClient::frame_received,
                   [&](const tracking::TrackedFrame& f) { ids.push_back(f.id); });
  QObject::connect(&client, &LeapWebSocketClient::device_changed,
                   [&](bool attached, bool) { device = attached; });
  client.start();
  ASSERT_TRUE(QTest::qWaitFor([&] { return ids.size() == 150; }, 10000)) << ids.size();
  EXPECT_TRUE(client.connected());
  EXPECT_TRUE(device);
  EXPECT_TRUE(client.hand_visible());
  EXPECT_EQ(client.service_version(), "2.3.1+33747");
  ASSERT_EQ(service->options.size(), 2u);
  EXPECT_EQ(service->options[0], R"({"background": true})");
  EXPECT_EQ(service->options[1], R"({"focused": true})");
  EXPECT_EQ(service->paths.front(), "/v6.json");

  // The service restarts on the same port; the client reconnects and goes on.
  service->shut_down();
  ASSERT_TRUE(QTest::qWaitFor([&] { return !client.connected(); }, 5000));
  service = std::make_unique<FakeLeapService>(port, messages, 150, 307);
  ASSERT_TRUE(QTest::qWaitFor([&] { return ids.size() == 307; }, 10000)) << ids.size();

  // Every frame, in order, none twice; also through the queue a session runner reads.
  const auto doc_ids = [&] {
    std::vector<std::int64_t> v;
    for (const auto& m : messages)
      v.push_back(std::int64_t(util::JsonValue::parse(m)["id"].as_number()));
    return v;
  }();
  EXPECT_EQ(ids, doc_ids);
  std::size_t queued = 0;
  while (client.queue().next()) ++queued;
  EXPECT_EQ(queued, 307u);
  EXPECT_EQ(client.messages_rejected(), 0);
  client.stop();
}

TEST(LeapWebSocketClient, StepsDownWhenTheServiceRefusesV6) {
  const auto messages = recording_messages();
  FakeLeapService service(0, messages, 0, 5, /*refuse_v6=*/true);
  LeapClientOptions options;
  options.server = QUrl(QString("ws://127.0.0.1:%1").arg(service.port()));
  LeapWebSocketClient client(options);
  int frames = 0;
  QObject::connect(&client, &LeapWebSocketClient::frame_received,
                   [&](const tracking::TrackedFrame&) { ++frames; });
  client.start();
  ASSERT_TRUE(QTest::qWaitFor([&] { return frames == 5; }, 10000));
  ASSERT_GE(service.paths.size(), 2u);
  EXPECT_EQ(service.paths[0], "/v6.json");
  EXPECT_EQ(service.paths[1], "/v5.json");
  client.stop();
}

TEST(LeapWebSocketClient, BadMessagesAreCountedNotFatal) {
  QWebSocketServer server("bad", QWebSocketServer::NonSecureMode);
  ASSERT_TRUE(server.listen(QHostAddress::LocalHost, 0));
  std::unique_ptr<QWebSocket> peer;
  QObject::connect(&server, &QWebSocketServer::newConnection, [&] {
    peer.reset(server.nextPendingConnection());
    peer->sendTextMessage("{not json");
    peer->sendTextMessage(R"({"id": 1, "timestamp": 5, "hands": [{"id": 1, "type": "right"}]})");
    peer->sendTextMessage(R"({"id": 2, "timestamp": 6, "hands": [], "pointables": []})");
  });
  LeapClientOptions options;
  options.server = QUrl(QString("ws://127.0.0.1:%1").arg(server.serverPort()));
  LeapWebSocketClient client(options);
  client.start();
  ASSERT_TRUE(QTest::qWaitFor([&] { return client.frames_received() == 1; }, 10000));
  EXPECT_EQ(client.messages_rejected(), 2);
  client.stop();
}

// The replay server a lab uses without a device (and scripts/live-latency.sh): the client
// greets it, sees the device stream, and receives the recording frame for frame, then its
// second loop with ids and timestamps that keep increasing by the loop's length.
TEST(LeapReplayServer, ServesARecordingFrameForFrameAndLoopsWithIncreasingIds) {
  const auto recording =
      tracking::read_recording(std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz");
  const std::size_t n = recording.frames.size();
  LeapReplayServer server(recording.frames, {/*port=*/0, /*loop=*/true});
  QString error;
  ASSERT_TRUE(server.start(&error)) << error.toStdString();
  EXPECT_NEAR(server.frame_rate_hz(),
              double(n - 1) / (recording.frames.back().timestamp - recording.frames[0].timestamp),
              1e-9);

  LeapClientOptions options;
  options.server = QUrl(QString("ws://127.0.0.1:%1").arg(server.port()));
  LeapWebSocketClient client(options);
  std::vector<tracking::TrackedFrame> got;
  QObject::connect(&client, &LeapWebSocketClient::frame_received,
                   [&](const tracking::TrackedFrame& f) { got.push_back(f); });
  client.start();
  // Frames sent before the client connected are not its; wait for a loop and a half.
  ASSERT_TRUE(QTest::qWaitFor([&] { return got.size() >= n + n / 2; }, 20000)) << got.size();
  EXPECT_EQ(client.service_version(), "handlab replay");
  EXPECT_TRUE(client.device_streaming());
  EXPECT_EQ(client.messages_rejected(), 0);
  for (std::size_t k = 1; k < got.size(); ++k) {
    ASSERT_GT(got[k].id, got[k - 1].id) << k;
    ASSERT_GT(got[k].timestamp, got[k - 1].timestamp) << k;
  }
  // Each received frame is the recording's frame at its place in the loop, its joints as
  // recorded; the loop adds whole loop lengths to ids and timestamps.
  const double length = recording.frames.back().timestamp - recording.frames[0].timestamp;
  const double period = length + length / double(n - 1);
  const std::int64_t id_step = recording.frames.back().id - recording.frames[0].id + 1;
  int looped = 0;
  for (const auto& f : got) {
    const std::int64_t offset = (f.id - recording.frames[0].id) / id_step;
    looped = std::max(looped, int(offset));
    const auto same = std::find_if(recording.frames.begin(), recording.frames.end(),
                                   [&](const auto& r) { return r.id == f.id - offset * id_step; });
    ASSERT_NE(same, recording.frames.end()) << f.id;
    EXPECT_NEAR(f.timestamp, same->timestamp + double(offset) * period, 2e-6);
    ASSERT_EQ(f.hands.size(), same->hands.size());
    if (!f.hands.empty()) {
      EXPECT_LT((f.hands[0].joints[1][4] - same->hands[0].joints[1][4]).norm(), 1e-9);
    }
  }
  EXPECT_GE(looped, 1) << "the second loop was served";
  client.stop();
}

}  // namespace
}  // namespace handlab::live

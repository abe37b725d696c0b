#include "app/gui/leap_link.h"

#include <QThread>
#include <QUrl>

#include "app/live/leap_websocket_client.h"

namespace handlab::gui {

LeapLink::LeapLink(QObject* parent) : QObject(parent) {}

LeapLink::~LeapLink() {
  drop();
  if (thread_) {
    thread_->quit();
    thread_->wait();
  }
}

void LeapLink::connect_to(const QString& address) {
  if (client_ && address_ == address) return;
  drop();
  live::LeapClientOptions options;
  options.server = QUrl(address);
  address_ = address;
  if (!thread_) {
    thread_ = new QThread(this);
    thread_->setObjectName("leap");
    thread_->start();
  }
  client_ = new live::LeapWebSocketClient(options);
  client_->moveToThread(thread_);
  connected_ = streaming_ = hand_ = false;
  connect(client_, &live::LeapWebSocketClient::connection_changed, this, [this](bool on) {
    connected_ = on;
    if (!on) hand_ = false;
    show_state();
  });
  connect(client_, &live::LeapWebSocketClient::device_changed, this, [this](bool, bool streaming) {
    streaming_ = streaming;
    show_state();
  });
  connect(client_, &live::LeapWebSocketClient::hand_visibility_changed, this, [this](bool on) {
    hand_ = on;
    streaming_ = streaming_ || on;
    show_state();
  });
  QMetaObject::invokeMethod(client_, &live::LeapWebSocketClient::start, Qt::QueuedConnection);
  show_state();
}

void LeapLink::drop() {
  if (!client_) return;
  live::LeapWebSocketClient* client = client_;
  client_ = nullptr;
  // Deleted on its own thread, where its socket lives.
  QMetaObject::invokeMethod(
      client, [client] { delete client; }, Qt::BlockingQueuedConnection);
}

void LeapLink::show_state() {
  emit state_changed(!connected_   ? tr("not connected (retrying)")
                     : !streaming_ ? tr("connected, no device streaming")
                     : hand_       ? tr("device streaming, hand seen")
                                   : tr("device streaming, no hand"));
}

}  // namespace handlab::gui

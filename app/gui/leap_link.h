// The live Leap Motion client of the session screen, on a thread of its own (frames arrive,
// and their arrival is timed, while the window draws), and what it says of the device in
// words for the experimenter.
#pragma once

#include <QObject>
#include <QString>

class QThread;

namespace handlab::live {
class LeapWebSocketClient;
}  // namespace handlab::live

namespace handlab::gui {

class LeapLink : public QObject {
  Q_OBJECT

 public:
  explicit LeapLink(QObject* parent = nullptr);
  ~LeapLink() override;

  // A client of `address` (the one there, or a new one in place of another address's).
  void connect_to(const QString& address);
  // No client (its thread stays for the next).
  void drop();
  // The client, or null.
  live::LeapWebSocketClient* client() const { return client_; }
  const QString& address() const { return address_; }

 signals:
  // "not connected (retrying)", "connected, no device streaming", ...
  void state_changed(const QString& text);

 private:
  void show_state();

  QThread* thread_ = nullptr;
  live::LeapWebSocketClient* client_ = nullptr;
  QString address_;
  bool connected_ = false, streaming_ = false, hand_ = false;
};

}  // namespace handlab::gui

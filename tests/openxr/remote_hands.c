// Drives Monado's remote driver (src/xrt/drivers/remote) as its debugging UI does: connects to
// the hub's TCP port and sends the state of a head and two hands, 100 times a second for the
// given seconds. Each hand's fingers close and open (curl 0 to 1 and back, every 2 s), the
// index a quarter of a cycle ahead, so that the runtime's hand joints move; with a third
// argument `open`, the right hand alone, held open and still (an open palm, as a session's
// calibration asks). Where the runtime's instance ends (the hub closes), it connects again to
// the next one.
// Built against Monado's own header (r_interface.h) by tests/openxr/openxr-test.sh.
#include <arpa/inet.h>
#include <math.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "r_interface.h"

static int held_open = 0;

static void hand(struct r_remote_controller_data* c, float x, double t) {
  memset(c, 0, sizeof(*c));
  c->pose.orientation.w = 1.0f;
  c->pose.position.x = x;
  c->pose.position.y = 1.3f;  // 0.3 m below the head
  c->pose.position.z = -0.4f;
  for (int f = 0; f < 5; ++f) {
    const double phase = 2 * M_PI * t / 2.0 + (f == 3 ? M_PI / 2 : 0.0);
    c->hand_curl[f] = held_open ? 0.0f : (float)(0.5 - 0.5 * cos(phase));
  }
  c->hand_tracking_active = true;
  c->active = true;
}

// A connection to the hub, trying for up to `seconds` (it listens once the runtime starts);
// -1 if none came.
static int connect_to_hub(const struct sockaddr_in* address, double seconds) {
  for (int attempt = 0; attempt < seconds * 50; ++attempt) {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (connect(fd, (const struct sockaddr*)address, sizeof(*address)) == 0) return fd;
    close(fd);
    usleep(20000);
  }
  return -1;
}

int main(int argc, char** argv) {
  if (argc != 3 && !(argc == 4 && strcmp(argv[3], "open") == 0)) {
    fprintf(stderr, "usage: remote_hands PORT SECONDS [open]\n");
    return 2;
  }
  held_open = argc == 4;
  const int port = atoi(argv[1]);
  const double seconds = atof(argv[2]);
  struct sockaddr_in address = {0};
  address.sin_family = AF_INET;
  address.sin_port = htons((uint16_t)port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  int fd = connect_to_hub(&address, 10.0);
  if (fd < 0) {
    fprintf(stderr, "remote_hands: no hub on port %d\n", port);
    return 1;
  }
  const int steps = (int)(seconds * 100);
  for (int i = 0; i < steps; ++i) {
    const double t = i / 100.0;
    struct r_remote_data data;
    memset(&data, 0, sizeof(data));
    data.header = R_HEADER_VALUE;
    // Monado's LOCAL space has its origin 1.6 m above the remote driver's tracking origin: the
    // head there, level, as a seated participant's at the session's start.
    data.head.center.orientation.w = 1.0f;
    data.head.center.position.y = 1.6f;
    hand(&data.left, -0.1f, t);
    data.left.active = data.left.hand_tracking_active = !held_open;
    hand(&data.right, 0.1f, t);
    if (send(fd, &data, sizeof(data), MSG_NOSIGNAL) != (ssize_t)sizeof(data)) {
      // The runtime's instance ended (one that only asked what the runtime offers, say): its
      // next one opens the hub again; none within the time left is the runtime gone.
      close(fd);
      fd = connect_to_hub(&address, (steps - i) / 100.0);
      if (fd < 0) return 0;
    }
    usleep(10000);
  }
  close(fd);
  return 0;
}

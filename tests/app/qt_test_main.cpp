// GoogleTest main for Qt widget tests: one QApplication for all tests, on the X server when
// there is one (ctest -L gui under xvfb-run), else offscreen, unless QT_QPA_PLATFORM says.
#include <QApplication>
#include <QSurfaceFormat>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  // Under an X server (xvfb-run) the real platform; without one, offscreen. (The offscreen
  // platform with a DISPLAY set takes GLX and crashes flushing an OpenGL widget.)
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
    qputenv("QT_QPA_PLATFORM", qEnvironmentVariableIsEmpty("DISPLAY") ? "offscreen" : "xcb");
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

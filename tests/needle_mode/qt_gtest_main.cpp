// main() of the trainer's window tests: the GL format the trainer uses (no multisampling, which
// the translucent passes need under Mesa) and a QApplication before any test makes a widget.

#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QSurfaceFormat>

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat([] {
    auto format = QVTKOpenGLNativeWidget::defaultFormat();
    format.setSamples(0);
    return format;
  }());
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

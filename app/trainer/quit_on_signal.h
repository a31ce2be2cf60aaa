#pragma once
// SIGTERM, SIGINT and SIGHUP end the trainer the way Quit does (the running session is stored
// as unfinished) instead of killing it: the handler only writes a byte to a pipe, and Qt's event
// loop reads it and quits. Call once, after the QApplication exists.

class QCoreApplication;

namespace vesica::app {

void QuitOnTerminationSignals(QCoreApplication& app);

}  // namespace vesica::app

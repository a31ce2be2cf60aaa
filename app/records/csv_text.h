#pragma once
// Text of one CSV field (RFC 4180) and of a number that reads back exactly: the records' export
// and the pending-sessions file write the same way.

#include <string>

namespace vesica::app {

/// `text` as one CSV field: quoted, with quotes doubled, when it holds a comma, a quote or a line end.
std::string CsvField(const std::string& text);

/// The shortest text that parses back to the same double.
std::string ShortestDoubleText(double value);

}  // namespace vesica::app

// Prints docs/protocol.md's generated tables with their markers, for pasting after a table change.
#include <iostream>

#include "firmware_protocol/docgen/protocol_tables.h"

int main() {
  for (const std::string& name : vesica::fp::protocol_table_names()) {
    std::cout << "<!-- BEGIN GENERATED: " << name << " -->\n"
              << vesica::fp::protocol_table(name) << "<!-- END GENERATED: " << name << " -->\n\n";
  }
  return 0;
}

// vesica-wireshark-dissector [OUTPUT.lua]: writes the generated Lua dissector to OUTPUT (stdout
// without an argument).
#include <cstdio>
#include <fstream>
#include <iostream>

#include "firmware_protocol/wireshark/wireshark_dissector.h"

int main(int argc, char** argv) {
  if (argc > 2) {
    std::cerr << "usage: " << argv[0] << " [OUTPUT.lua]\n";
    return 2;
  }
  const std::string lua = vesica::fp::wireshark_dissector_lua();
  if (argc == 1) {
    std::cout << lua;
    return std::cout.good() ? 0 : 1;
  }
  std::ofstream out(argv[1], std::ios::binary);
  out << lua;
  out.close();
  if (!out) {
    std::perror(argv[1]);
    return 1;
  }
  return 0;
}

// tshark -T fields into a file; HOME points at the scratch directory so no personal Wireshark
// profile or plugin changes what is decoded.
#include "tshark_runner.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vesica::fp::test {

std::vector<TsharkRow> run_tshark(const std::string& tshark, const std::filesystem::path& capture,
                                  const std::filesystem::path& lua, const std::vector<std::string>& fields,
                                  const std::filesystem::path& work) {
  const auto out_path = work / "tshark.out";
  const auto err_path = work / "tshark.err";
  std::ostringstream cmd;
  cmd << "HOME=" << work << " XDG_CONFIG_HOME=" << work << " " << tshark << " -n -r " << capture
      << " -X lua_script:" << lua << " -T fields -E separator=/t -E occurrence=a -E aggregator=,";
  for (const std::string& f : fields) cmd << " -e " << f;
  cmd << " > " << out_path << " 2> " << err_path;
  const int status = std::system(cmd.str().c_str());
  std::ifstream err_file(err_path);
  const std::string err((std::istreambuf_iterator<char>(err_file)), std::istreambuf_iterator<char>());
  if (status != 0) throw std::runtime_error("tshark failed (" + std::to_string(status) + "): " + cmd.str() + "\n" + err);
  if (err.find("Lua") != std::string::npos) throw std::runtime_error("tshark reported a Lua problem:\n" + err);

  std::vector<TsharkRow> rows;
  std::ifstream out(out_path);
  std::string line;
  while (std::getline(out, line)) {
    TsharkRow row;
    std::size_t start = 0;
    for (const std::string& f : fields) {
      const std::size_t tab = line.find('\t', start);
      row[f] = line.substr(start, tab == std::string::npos ? std::string::npos : tab - start);
      start = tab == std::string::npos ? line.size() : tab + 1;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace vesica::fp::test

// vesica-armsim's fixture control: the reference load and a hand, moved from standard input.
#include "app/armsim/fixture_control.h"

#include <poll.h>
#include <unistd.h>

#include <cstdio>
#include <sstream>

#include "firmware_protocol/emulator/arm_geometry.h"
#include "firmware_protocol/emulator/reference_load.h"

namespace vesica::app {

namespace emu = fp::emulator;

std::string FixtureControl::Apply(const std::string& line, emu::ArmPlant& plant) {
  std::istringstream in(line);
  std::string command;
  in >> command;
  if (command == "reference-load") {
    std::string state;
    in >> state;
    if (state != "on" && state != "off") return "error " + line + ": reference-load takes on or off";
    plant.SetReferenceLoad(state == "on" ? emu::StandardReferenceLoad() : emu::ReferenceLoad{});
    return "ok " + line;
  }
  if (command == "let-go") {
    holding_ = false;
    emu::HandTarget let_go;
    let_go.holding = false;
    plant.SetHandScript(emu::HandScript(let_go));
    return "ok " + line;
  }
  if (command == "hand") {
    emu::HandTarget next = target_;
    if (!holding_) {  // taking hold: where the instrument is, as it is
      next.roll_rad = plant.q()[2];
      next.jaw_rad = 0.0;
      next.pedal_travel = 0.0;
    }
    next.holding = true;
    next.p_T = emu::TipPosition(plant.q());  // the other hand keeps the instrument where it is
    std::string word;
    while (in >> word) {
      const auto eq = word.find('=');
      double value = 0.0;
      try {
        if (eq == std::string::npos) throw std::invalid_argument(word);
        std::size_t used = 0;
        value = std::stod(word.substr(eq + 1), &used);
        if (used != word.size() - eq - 1) throw std::invalid_argument(word);
      } catch (const std::exception&) {
        return "error " + line + ": '" + word + "' is not NAME=NUMBER";
      }
      const std::string name = word.substr(0, eq);
      if (name == "roll")
        next.roll_rad = value;
      else if (name == "jaw")
        next.jaw_rad = value;
      else if (name == "pedal" && value >= 0.0 && value <= 1.0)
        next.pedal_travel = value;
      else
        return "error " + line + ": unknown '" + word + "' (roll=RAD, jaw=RAD, pedal=0..1)";
    }
    emu::HandTarget from = holding_ ? target_ : next;
    from.p_T = next.p_T;
    emu::HandScript script;
    script.Add(plant.time_s(), from);
    script.Add(plant.time_s() + 0.4, next);
    plant.SetHandScript(script);
    target_ = next;
    holding_ = true;
    return "ok " + line;
  }
  return "error " + line + ": unknown command (reference-load on|off, hand ..., let-go)";
}

bool FixtureControl::Poll(emu::ArmPlant& plant) {
  if (!open_) return false;
  pollfd p{STDIN_FILENO, POLLIN, 0};
  while (::poll(&p, 1, 0) > 0 && (p.revents & (POLLIN | POLLHUP)) != 0) {
    char buf[256];
    const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
    if (n <= 0) {
      open_ = false;
      break;
    }
    pending_.append(buf, static_cast<std::size_t>(n));
  }
  for (auto end = pending_.find('\n'); end != std::string::npos; end = pending_.find('\n')) {
    const std::string line = pending_.substr(0, end);
    pending_.erase(0, end + 1);
    if (line.empty()) continue;
    std::printf("%s\n", Apply(line, plant).c_str());
    std::fflush(stdout);
  }
  return open_;
}

}  // namespace vesica::app

// The right hand's port: the exchange order, the button's press edge, and the scenario's list.
#include "app/session/tool_exchange.h"

#include <gtest/gtest.h>

#include <fstream>

#include "app/scenario/scenario_loader.h"
#include "app/session/live_input.h"

namespace vesica::app {
namespace {

using physics::InstrumentTool;

TEST(ToolExchange, CyclesThroughThePortsToolsAndBack) {
  ToolExchange port({InstrumentTool::kCauteryHook, InstrumentTool::kClipApplier, InstrumentTool::kScissors});
  EXPECT_EQ(port.current(), InstrumentTool::kCauteryHook);
  EXPECT_EQ(port.Next(), InstrumentTool::kClipApplier);
  EXPECT_EQ(port.Next(), InstrumentTool::kScissors);
  EXPECT_EQ(port.Next(), InstrumentTool::kCauteryHook);
}

TEST(ToolExchange, OnePressOneExchangeHowEverLongTheButtonIsHeld) {
  ToolExchange port({InstrumentTool::kCauteryHook, InstrumentTool::kScissors});
  EXPECT_FALSE(port.OnButton(false));
  EXPECT_TRUE(port.OnButton(true));
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(port.OnButton(true));
  EXPECT_EQ(port.current(), InstrumentTool::kScissors);
  EXPECT_FALSE(port.OnButton(false));
  EXPECT_TRUE(port.OnButton(true));
  EXPECT_EQ(port.current(), InstrumentTool::kCauteryHook);
}

TEST(ToolExchange, APortWithOneToolKeepsIt) {
  ToolExchange port;
  EXPECT_FALSE(port.OnButton(true));
  EXPECT_EQ(port.Next(), InstrumentTool::kCauteryHook);
}

TEST(ToolExchange, RefusesAnEmptyPortTheGrasperAndRepeats) {
  EXPECT_THROW(ToolExchange(std::vector<InstrumentTool>{}), std::invalid_argument);
  EXPECT_THROW(ToolExchange({InstrumentTool::kCauteryHook, InstrumentTool::kGrasper}), std::invalid_argument);
  EXPECT_THROW(ToolExchange({InstrumentTool::kScissors, InstrumentTool::kScissors}), std::invalid_argument);
}

TEST(ToolExchange, TheDefaultScenarioKeepsTheHookAlone) {
  const ToolExchange port = RightPortExchange(LoadScenario(DefaultScenarioPath()));
  ASSERT_EQ(port.tools().size(), 1u);
  EXPECT_EQ(port.current(), InstrumentTool::kCauteryHook);
}

// The default scenario with `line` added to its hook's [[instruments]] table.
std::filesystem::path ScenarioWithHookLine(const std::string& line, const std::string& name) {
  std::ifstream in(DefaultScenarioPath());
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::size_t hook = text.find("kind = \"cautery_hook\"");
  EXPECT_NE(hook, std::string::npos);
  text.insert(text.find('\n', hook) + 1, line + "\n");
  const std::filesystem::path dir = DefaultScenarioPath().parent_path();
  const std::filesystem::path out = std::filesystem::path(testing::TempDir()) / name;
  // Relative mesh paths resolve against the scenario's folder: make them absolute.
  for (std::size_t at = 0; (at = text.find("\"../", at)) != std::string::npos;)
    text.replace(at + 1, 3, (dir / "..").string() + "/");
  std::ofstream(out) << text;
  return out;
}

TEST(ToolExchange, TheScenarioListsTheToolsAfterTheHook) {
  const Scenario s =
      LoadScenario(ScenarioWithHookLine("exchange = [\"clip_applier\", \"scissors\"]", "exchange.toml"));
  const ToolExchange port = RightPortExchange(s);
  ASSERT_EQ(port.tools().size(), 3u);
  EXPECT_EQ(port.tools()[1], InstrumentTool::kClipApplier);
  EXPECT_EQ(port.tools()[2], InstrumentTool::kScissors);
}

TEST(ToolExchange, ABadExchangeListNamesTheFileLineAndTool) {
  const auto expect_error = [](const std::string& line, const std::string& fragment) {
    const std::filesystem::path file = ScenarioWithHookLine(line, "bad_exchange.toml");
    try {
      LoadScenario(file);
      ADD_FAILURE() << "accepted " << line;
    } catch (const ScenarioError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file.string() + ":"), std::string::npos) << what;
      EXPECT_NE(what.find("exchange"), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
  };
  expect_error("exchange = [\"laser\"]", "unknown tool 'laser'");
  expect_error("exchange = [\"grasper\"]", "unknown tool 'grasper'");
  expect_error("exchange = [\"cautery_hook\"]", "twice");
  expect_error("exchange = [\"scissors\", \"scissors\"]", "twice");
  expect_error("exchange = \"scissors\"", "must be an array of strings");
  expect_error("exchange = [3]", "element 0 must be a string");
}

TEST(ToolExchange, TheKeyboardsToolReachesTheNextSample) {
  LiveInput input;
  EXPECT_EQ(input.Sample(0).right_tool, InstrumentTool::kCauteryHook);
  input.SetRightTool(InstrumentTool::kClipApplier);
  device::InstrumentInput moved;
  moved.pose.insertion_m = 0.07;
  input.Set(1, moved);  // moving the instrument keeps the tool
  const device::InputFrame f = input.Sample(0.01);
  EXPECT_EQ(f.right_tool, InstrumentTool::kClipApplier);
  EXPECT_EQ(f.instruments[1].pose.insertion_m, 0.07);
}

}  // namespace
}  // namespace vesica::app

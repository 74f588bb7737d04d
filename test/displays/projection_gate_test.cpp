// ProjectionGate without rviz's window (Qt offscreen): Visibility ticks stay with their displays
// when the list is reordered, a display above is removed or a new one added; the visibility
// signature and the frame decision follow what is shown, under rviz's and projector_host's render
// policy.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

#include <QApplication>
#include <ros/ros.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/properties/display_group_visibility_property.h>

#include "rviz_projector/displays/projection_gate.h"
#include "rviz_projector/displays/render_policy.h"

using rviz_projector::FrameState;
using rviz_projector::ProjectionGate;
using rviz_projector::RenderPolicy;

namespace
{
rviz::Display* display(const QString& class_id, const QString& name)
{
  auto* d = new rviz::Display();
  d->setClassId(class_id);
  d->setName(name);
  return d;
}

/// Enabled as far as the gate can see (Display::isEnabled()), without Display's enable handling,
/// which needs an rviz context this test does not have.
void enable(rviz::Display* d)
{
  const bool blocked = d->blockSignals(true);
  d->setValue(true);
  d->blockSignals(blocked);
}

/// The tick shown for the display named `name`, read from the property tree by name (what the
/// Displays panel shows and what a config saves).
bool tickNamed(rviz::Property* visibility, const QString& name)
{
  for (int i = 0; i < visibility->numChildren(); ++i)
  {
    if (visibility->childAt(i)->getName() == name)
    {
      return visibility->childAt(i)->getValue().toBool();
    }
  }
  ADD_FAILURE() << "no tick for " << name.toStdString();
  return false;
}

class ProjectionGateTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    group_ = std::make_unique<rviz::DisplayGroup>();
    group_->setName("root");
    enable(group_.get());  // rviz's root group is always enabled
    map_ = display("rviz/Map", "Map");
    path_ = display("rviz_projector/ProjectedPath", "Path");
    grid_ = display("rviz/Grid", "Grid");
    projector_ = display("rviz_projector/ProjectorCamera", "Projector");
    for (rviz::Display* d : {map_, path_, grid_, projector_})
    {
      group_->addDisplay(d);
    }
    // As ProjectorCameraDisplay::onInitialize: gate, then the property, then attach.
    gate_ = std::make_unique<ProjectionGate>(group_.get(), projector_, RenderPolicy::rviz());
    visibility_ = new rviz::DisplayGroupVisibilityProperty(1u << 5, group_.get(), projector_, "Visibility", true, "",
                                                           projector_);
    gate_->attach(visibility_);
  }

  void TearDown() override
  {
    gate_.reset();
    group_.reset();  // deletes the displays (and the property, a child of the projector)
  }

  /// A second gate of the same projector under `policy`, with a Visibility of its own in which
  /// the grid (a display of another package) is ticked and enabled.
  std::unique_ptr<ProjectionGate> gateShowingTheGrid(const RenderPolicy& policy)
  {
    auto gate = std::make_unique<ProjectionGate>(group_.get(), projector_, policy);
    auto* visibility = new rviz::DisplayGroupVisibilityProperty(1u << 6, group_.get(), projector_, "Visibility 2",
                                                                true, "", projector_);
    gate->attach(visibility);
    gate->tickOf(grid_)->setValue(true);
    enable(grid_);
    return gate;
  }

  static FrameState someState()
  {
    FrameState s;
    s.pose = {1, 2, 3, 1, 0, 0, 0};
    s.changes = 7;
    s.image = {0, 0, 1280, 800};
    s.drawable = true;
    return s;
  }

  std::unique_ptr<rviz::DisplayGroup> group_;
  std::unique_ptr<ProjectionGate> gate_;
  rviz::DisplayGroupVisibilityProperty* visibility_ = nullptr;
  rviz::Display *map_, *path_, *grid_, *projector_;
};
}  // namespace

TEST_F(ProjectionGateTest, DefaultsProjectOnlyThisPackagesPathDisplays)
{
  EXPECT_FALSE(tickNamed(visibility_, "Map"));
  EXPECT_TRUE(tickNamed(visibility_, "Path"));
  EXPECT_FALSE(tickNamed(visibility_, "Grid"));
  EXPECT_EQ(gate_->tickOf(path_)->getName(), "Path");
  EXPECT_EQ(gate_->tickOf(map_)->getName(), "Map");
}

TEST_F(ProjectionGateTest, MovingADisplayKeepsEveryTickWithItsDisplay)
{
  // Ticks unlike the defaults, so that a tick reset to its default is seen.
  gate_->tickOf(map_)->setValue(true);
  gate_->tickOf(path_)->setValue(false);
  gate_->tickOf(grid_)->setValue(true);
  // Drag and drop does what DisplayGroup::takeDisplay + addChild at another row do.
  group_->takeDisplay(map_);
  group_->addChild(map_, group_->Display::numChildren() + 2);  // below the grid
  EXPECT_TRUE(tickNamed(visibility_, "Map"));
  EXPECT_FALSE(tickNamed(visibility_, "Path"));
  EXPECT_TRUE(tickNamed(visibility_, "Grid"));
  // Move the unticked path to the top.
  group_->takeDisplay(path_);
  group_->addChild(path_, group_->Display::numChildren());
  EXPECT_TRUE(tickNamed(visibility_, "Map"));
  EXPECT_FALSE(tickNamed(visibility_, "Path"));
  EXPECT_TRUE(tickNamed(visibility_, "Grid"));
  EXPECT_EQ(group_->getDisplayAt(0), path_);
}

TEST_F(ProjectionGateTest, RemovingADisplayAboveAndAddingOneKeepTheOthersTicks)
{
  gate_->tickOf(grid_)->setValue(true);
  gate_->tickOf(path_)->setValue(false);
  rviz::Display* gone = group_->takeDisplay(map_);  // removed above the others
  delete gone;
  EXPECT_FALSE(tickNamed(visibility_, "Path"));
  EXPECT_TRUE(tickNamed(visibility_, "Grid"));
  rviz::Display* marker = display("rviz/Marker", "Marker");
  group_->addChild(marker, group_->Display::numChildren());  // added at the top
  EXPECT_FALSE(tickNamed(visibility_, "Marker"));  // a foreign display starts hidden
  EXPECT_FALSE(tickNamed(visibility_, "Path"));
  EXPECT_TRUE(tickNamed(visibility_, "Grid"));
  rviz::Display* second_path = display("rviz_projector/ProjectedPath", "Second path");
  group_->addDisplay(second_path);
  EXPECT_TRUE(tickNamed(visibility_, "Second path"));
}

TEST_F(ProjectionGateTest, SignatureFollowsTicksAndEnabledDisplays)
{
  const std::uint64_t before = gate_->visibilitySignature();
  EXPECT_EQ(gate_->visibilitySignature(), before);  // nothing changed: same value
  gate_->tickOf(grid_)->setValue(true);
  const std::uint64_t ticked = gate_->visibilitySignature();
  EXPECT_NE(ticked, before);
  enable(grid_);
  EXPECT_NE(gate_->visibilitySignature(), ticked);
  // Two displays swapping places changes the signature too (the list is walked in order).
  const std::uint64_t ordered = gate_->visibilitySignature();
  group_->takeDisplay(map_);
  group_->addDisplay(map_);
  EXPECT_NE(gate_->visibilitySignature(), ordered);
}

TEST_F(ProjectionGateTest, ForeignDisplaysCountOnlyWhenTickedAndEnabled)
{
  enable(path_);
  EXPECT_FALSE(gate_->showsForeignDisplays());  // ours only
  gate_->tickOf(grid_)->setValue(true);
  EXPECT_FALSE(gate_->showsForeignDisplays());  // ticked but disabled
  enable(grid_);
  EXPECT_TRUE(gate_->showsForeignDisplays());
  visibility_->setValue(false);  // the whole Visibility unticked
  EXPECT_FALSE(gate_->showsForeignDisplays());
}

TEST_F(ProjectionGateTest, AFrameIsNeededOnlyWhenSomethingChanged)
{
  FrameState s;
  s.pose = {1, 2, 3, 1, 0, 0, 0};
  s.changes = 7;
  s.visibility = gate_->visibilitySignature();
  s.image = {0, 0, 1280, 800};
  s.drawable = true;
  EXPECT_TRUE(gate_->needsFrame(s));   // first frame
  EXPECT_FALSE(gate_->needsFrame(s));  // the same again
  FrameState moved = s;
  moved.pose[0] = 1.001f;
  EXPECT_TRUE(gate_->needsFrame(moved));
  FrameState changed = moved;
  changed.changes = 8;
  EXPECT_TRUE(gate_->needsFrame(changed));
  FrameState letterboxed = changed;
  letterboxed.image = {0, 1, 1280, 799};
  EXPECT_TRUE(gate_->needsFrame(letterboxed));
  EXPECT_FALSE(gate_->needsFrame(letterboxed));
  gate_->invalidate();
  EXPECT_TRUE(gate_->needsFrame(letterboxed));
  // A ticked, enabled foreign display renders every tick (it does not announce changes).
  gate_->tickOf(grid_)->setValue(true);
  enable(grid_);
  EXPECT_TRUE(gate_->needsFrame(letterboxed));
  EXPECT_TRUE(gate_->needsFrame(letterboxed));
}

TEST_F(ProjectionGateTest, UnderRvizsPolicyAForeignDisplayRendersEveryTick)
{
  const std::unique_ptr<ProjectionGate> gate = gateShowingTheGrid(RenderPolicy::rviz());
  ASSERT_TRUE(gate->showsForeignDisplays());
  const FrameState s = someState();
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_TRUE(gate->needsFrame(s)) << "tick " << i;  // rviz's displays do not announce changes
  }
}

TEST_F(ProjectionGateTest, UnderTheHostsPolicyAForeignDisplayRendersOnlyOnChangeOrKeepAlive)
{
  // No keep-alive: an unchanged state (the grid's scene graph included) renders nothing more.
  const std::unique_ptr<ProjectionGate> quiet = gateShowingTheGrid(RenderPolicy::projectorHost(0.0));
  ASSERT_TRUE(quiet->showsForeignDisplays());
  FrameState s = someState();
  EXPECT_TRUE(quiet->needsFrame(s));
  EXPECT_FALSE(quiet->needsFrame(s));
  EXPECT_FALSE(quiet->needsFrame(s));
  s.changes = 8;  // a change of this package's displays still renders
  EXPECT_TRUE(quiet->needsFrame(s));
  EXPECT_FALSE(quiet->needsFrame(s));

  // A keep-alive of 50 ms: one frame once the period passed since the last one.
  const std::unique_ptr<ProjectionGate> kept = gateShowingTheGrid(RenderPolicy::projectorHost(0.05));
  EXPECT_TRUE(kept->needsFrame(s));
  EXPECT_FALSE(kept->needsFrame(s));
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  EXPECT_TRUE(kept->needsFrame(s));
  EXPECT_FALSE(kept->needsFrame(s));
}

TEST(RenderPolicy, TheProcessPolicyIsRvizsUntilTheHostSetsItsOwn)
{
  EXPECT_FALSE(rviz_projector::processRenderPolicy().host);
  EXPECT_EQ(rviz_projector::processRenderPolicy().keep_alive_s, rviz_projector::kHostKeepAliveSeconds);
  rviz_projector::setProcessRenderPolicy(RenderPolicy::projectorHost(2.5));
  EXPECT_TRUE(rviz_projector::processRenderPolicy().host);
  EXPECT_EQ(rviz_projector::processRenderPolicy().keep_alive_s, 2.5);
  EXPECT_EQ(RenderPolicy::projectorHost(-1.0).keep_alive_s, 0.0);  // no negative period
  rviz_projector::setProcessRenderPolicy(RenderPolicy::rviz());
  EXPECT_FALSE(rviz_projector::processRenderPolicy().host);
}

int main(int argc, char** argv)
{
  // No X server needed: Qt's offscreen platform (rviz's properties use QApplication's cursor).
  qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  // rviz's displays own node handles (run under rostest: they register with its master).
  ros::init(argc, argv, "test_projection_gate", ros::init_options::AnonymousName);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

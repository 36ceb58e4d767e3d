// The desktop tool's window features that are not drawing: recent files, the file dialog's
// listing and typed paths, picking and measuring, colour by the file's attributes and the legends,
// the scale bar and axis gizmo, the unsaved-work question and the help overlay's key list.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "test_support.h"
#include "treesketch/render/color_map.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/action_script.h"
#include "treesketch/viewer/attribute_colors.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/file_browser.h"
#include "treesketch/viewer/key_bindings.h"
#include "treesketch/viewer/picking.h"
#include "treesketch/viewer/recent_files.h"
#include "treesketch/viewer/unsaved_work.h"
#include "treesketch/viewer/view_overlays.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {
namespace {

namespace fs = std::filesystem;
using geom::Vec2;
using geom::Vec3;

// ---- recent files -------------------------------------------------------------------------------

TEST(RecentFiles, NewestFirstNoDuplicatesAtMostTen) {
  RecentFiles r;
  for (int i = 0; i < 12; ++i) r.add(RecentKind::Cloud, "/data/c" + std::to_string(i) + ".las");
  r.add(RecentKind::Sketch, "/data/c5.las");  // same path, other kind: a separate entry
  r.add(RecentKind::Cloud, "/data/c5.las");   // moves to the front
  ASSERT_EQ(r.entries().size(), RecentFiles::kMaxEntries);
  EXPECT_EQ(r.entries()[0].path, fs::path("/data/c5.las"));
  EXPECT_EQ(r.entries()[0].kind, RecentKind::Cloud);
  EXPECT_EQ(r.entries()[1].kind, RecentKind::Sketch);
  EXPECT_EQ(r.entries()[2].path, fs::path("/data/c11.las"));
  EXPECT_EQ(r.entries(RecentKind::Sketch).size(), 1u);
  r.add(RecentKind::Cloud, "relative/x.xyz");
  EXPECT_TRUE(r.entries()[0].path.is_absolute());
}

TEST(RecentFiles, RoundTripThroughAFile) {
  test::TempDir dir;
  fs::path file = recentFilesPath(dir / "config" / "treesketch");
  RecentFiles r;
  r.add(RecentKind::Cloud, "/a/tree one.las");  // spaces in a path
  r.add(RecentKind::Sketch, "/a/tree.sketch.json");
  EXPECT_EQ(r.save(file), "");  // creates the folders
  RecentFiles back;
  EXPECT_EQ(back.load(file), "");
  EXPECT_EQ(back.entries(), r.entries());
}

TEST(RecentFiles, MissingFileIsEmptyCorruptFileIsIgnoredWithAMessage) {
  test::TempDir dir;
  RecentFiles r;
  EXPECT_EQ(r.load(dir / "none.txt"), "");
  EXPECT_TRUE(r.entries().empty());
  test::writeText(dir / "bad.txt", "treesketch-recent 1\ncloud\t/a.las\nthis line is wrong\n");
  std::string m = r.load(dir / "bad.txt");
  EXPECT_NE(m.find("bad.txt:3"), std::string::npos) << m;
  EXPECT_NE(m.find("ignored"), std::string::npos) << m;
  EXPECT_TRUE(r.entries().empty());
  test::writeText(dir / "binary.txt", std::string("\x00\x01\x02garbage", 10));
  EXPECT_NE(r.load(dir / "binary.txt"), "");
  test::writeText(dir / "empty.txt", "");
  EXPECT_NE(r.load(dir / "empty.txt"), "");
}

TEST(RecentFiles, ConfigDirectoryFollowsXdg) {
  const char* oldXdg = std::getenv("XDG_CONFIG_HOME");
  std::string saved = oldXdg ? oldXdg : "";
  setenv("XDG_CONFIG_HOME", "/tmp/xdg_test_home", 1);
  EXPECT_EQ(configDirectory(), fs::path("/tmp/xdg_test_home/treesketch"));
  unsetenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  if (home && *home) EXPECT_EQ(configDirectory(), fs::path(home) / ".config" / "treesketch");
  if (oldXdg) setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
}

// ---- file browser --------------------------------------------------------------------------------

TEST(FileBrowser, FoldersFirstThenMatchingFilesSortedByName) {
  test::TempDir dir;
  fs::create_directories(dir / "zeta");
  fs::create_directories(dir / "Alpha");
  fs::create_directories(dir / ".hidden_dir");
  for (const char* f : {"b.LAS", "a.xyz", "notes.md", "C.ply", ".secret.xyz", "mesh.obj", "s.json"})
    test::writeText(dir / f, "x");
  DirectoryListing l = listDirectory(dir.path(), cloudFileFilter());
  ASSERT_TRUE(l.ok()) << l.error;
  std::vector<std::string> names;
  for (const FileEntry& e : l.entries) names.push_back((e.directory ? "/" : "") + e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"/..", "/Alpha", "/zeta", "a.xyz", "b.LAS", "C.ply", "mesh.obj"}));
  DirectoryListing all = listDirectory(dir.path(), allFilesFilter(), true);
  EXPECT_EQ(all.entries.size(), 1u + 3u + 7u);
  DirectoryListing sk = listDirectory(dir.path(), sketchFileFilter());
  EXPECT_EQ(sk.entries.back().name, "s.json");
}

TEST(FileBrowser, MissingFolderIsAnErrorInTheListingNotAnException) {
  test::TempDir dir;
  DirectoryListing l = listDirectory(dir / "nope", cloudFileFilter());
  EXPECT_FALSE(l.ok());
  EXPECT_NE(l.error.find("no such folder"), std::string::npos);
  EXPECT_TRUE(l.entries.empty());
  test::writeText(dir / "file.xyz", "1 2 3");
  EXPECT_NE(listDirectory(dir / "file.xyz", cloudFileFilter()).error.find("not a folder"), std::string::npos);
}

TEST(FileBrowser, TypedPathsAndSaveNames) {
  fs::path cur = "/data/plots";
  EXPECT_EQ(resolveTypedPath(cur, "tree.las"), fs::path("/data/plots/tree.las"));
  EXPECT_EQ(resolveTypedPath(cur, "../other/"), fs::path("/data/other"));
  EXPECT_EQ(resolveTypedPath(cur, "/abs/x.xyz"), fs::path("/abs/x.xyz"));
  EXPECT_EQ(resolveTypedPath(cur, "  "), cur);
  const char* home = std::getenv("HOME");
  if (home && *home) EXPECT_EQ(resolveTypedPath(cur, "~/t.ply"), fs::path(home) / "t.ply");
  EXPECT_EQ(pathForSave(cur, "tree", sketchFileFilter()), fs::path("/data/plots/tree.json"));
  EXPECT_EQ(pathForSave(cur, "tree.obj", meshFileFilter()), fs::path("/data/plots/tree.obj"));
  EXPECT_TRUE(cloudFileFilter().matches("X.LAS"));
  EXPECT_TRUE(cloudFileFilter().matches("x.laz"));
  EXPECT_TRUE(cloudFileFilter().matches("scan.asc"));
  EXPECT_FALSE(cloudFileFilter().matches("x.e57"));
  EXPECT_EQ(meshFileFilter().label(), "Meshes (*.obj *.ply)");
}

// ---- picking and measuring -------------------------------------------------------------------------

geom::Camera frontCamera() {
  geom::Camera cam;
  cam.viewport = geom::Viewport{0, 0, 400, 400};
  cam.view = geom::lookAt(Vec3(0, 0, 10), Vec3(0, 0, 0), Vec3(0, 1, 0));
  cam.projection = geom::perspective(30, 1.0, 0.1, 100);
  return cam;
}

TEST(Picking, TheNearestVisiblePointUnderTheClickWins) {
  geom::PointCloud c;
  c.positions = {Vec3(0, 0, -2), Vec3(0, 0, 1), Vec3(0.001, 0, 3), Vec3(2, 2, 0)};
  geom::Camera cam = frontCamera();
  Vec3 s = cam.project(Vec3(0, 0, 0));
  PickedPoint p = pickPoint(c, cam, Vec2(s.x(), s.y()), 5.0);
  ASSERT_TRUE(p.found);
  EXPECT_EQ(p.index, 2u);  // z = 3 is nearest the eye at z = 10, though 0.001 off the ray
  EXPECT_EQ(p.position, c.positions[2]);
  Vec3 corner = cam.project(Vec3(2, 2, 0));
  PickedPoint q = pickPoint(c, cam, Vec2(corner.x() + 3, corner.y()), 5.0);
  ASSERT_TRUE(q.found);
  EXPECT_EQ(q.index, 3u);
  EXPECT_NEAR(q.screenDistancePx, 3.0, 1e-6);
  EXPECT_FALSE(pickPoint(c, cam, Vec2(corner.x() + 8, corner.y()), 5.0).found);
  EXPECT_FALSE(pickPoint(geom::PointCloud{}, cam, Vec2(200, 200), 5.0).found);
  EXPECT_FALSE(pickPoint(c, cam, Vec2(s.x(), s.y()), 0.0).found);
}

TEST(Picking, PointsBehindTheEyeAreNeverPicked) {
  geom::PointCloud c;
  c.positions = {Vec3(0, 0, 20)};  // behind the eye at z = 10 looking down -z
  EXPECT_FALSE(pickPoint(c, frontCamera(), Vec2(200, 200), 50.0).found);
}

TEST(Picking, MeasurementSplitsAlongAndAcrossUp) {
  Measurement m = measure(Vec3(1, 2, 3), Vec3(4, 6, 3), geom::UpAxis::Y);
  EXPECT_DOUBLE_EQ(m.distance, 5.0);
  EXPECT_DOUBLE_EQ(m.vertical, 4.0);
  EXPECT_DOUBLE_EQ(m.horizontal, 3.0);
  Measurement z = measure(Vec3(0, 0, 0), Vec3(0, 3, -4), geom::UpAxis::Z);
  EXPECT_DOUBLE_EQ(z.vertical, 4.0);
  EXPECT_DOUBLE_EQ(z.horizontal, 3.0);
  EXPECT_EQ(z.delta, Vec3(0, 3, -4));
}

TEST(Picking, SessionMeasuresEverySecondPick) {
  PickSession s;
  PickedPoint a{true, 0, Vec3(0, 0, 0), 0}, b{true, 1, Vec3(0, 0, 2), 0}, none{};
  EXPECT_FALSE(s.add(none));
  EXPECT_EQ(s.count(), 0);
  s.add(a);
  EXPECT_FALSE(s.hasMeasurement());
  s.add(b);
  ASSERT_TRUE(s.hasMeasurement());
  EXPECT_DOUBLE_EQ(s.measurement(geom::UpAxis::Z).distance, 2.0);
  s.add(b);  // a third pick starts again
  EXPECT_EQ(s.count(), 1);
  EXPECT_EQ(s.first().index, 1u);
}

TEST(Picking, DescribePointListsTheAttributesTheCloudHas) {
  geom::PointCloud c;
  c.positions = {Vec3(1, 2, 3), Vec3(4, 5, 6)};
  EXPECT_EQ(describePoint(c, 1).size(), 1u);
  c.intensity = {10, 20};
  c.color = {{1, 2, 3}, {4, 5, 6}};
  c.classification = {2, 5};
  std::vector<std::string> d = describePoint(c, 1);
  ASSERT_EQ(d.size(), 4u);
  EXPECT_NE(d[0].find("x 4.0000"), std::string::npos);
  EXPECT_EQ(d[1], "intensity 20");
  EXPECT_EQ(d[2], "RGB 4 5 6");
  EXPECT_EQ(d[3], "class 5 (high vegetation)");
  EXPECT_TRUE(describePoint(c, 2).empty());
}

// ---- colours and legends -------------------------------------------------------------------------------

TEST(AttributeColors, ClassNamesAndColours) {
  EXPECT_EQ(asprsClassName(2), "ground");
  EXPECT_EQ(asprsClassName(5), "high vegetation");
  EXPECT_EQ(asprsClassName(7), "low point (noise)");
  EXPECT_EQ(asprsClassName(40), "reserved");
  EXPECT_EQ(asprsClassName(200), "user defined");
  EXPECT_NE(classificationColor(2), classificationColor(5));
  std::vector<Rgb> cols = classificationColors({2, 5, 2});
  EXPECT_EQ(cols[0], cols[2]);
  EXPECT_EQ(cols[1], classificationColor(5));
}

TEST(AttributeColors, IntensityRangeIgnoresTheFewExtremeReturns) {
  std::vector<float> v;
  for (int i = 0; i < 1000; ++i) v.push_back(static_cast<float>(i % 100));
  v[5] = 65535.0f;  // one saturated return
  ValueRange r = quantileRange(v);
  EXPECT_LE(r.max, 99.0);
  EXPECT_GE(r.min, 0.0);
  std::vector<Rgb> c = intensityColors({0.0f, 50.0f, 100.0f, 65535.0f}, ValueRange{0, 100});
  EXPECT_EQ(c[0], (Rgb{0, 0, 0}));
  EXPECT_EQ(c[2], (Rgb{255, 255, 255}));
  EXPECT_EQ(c[3], c[2]);  // clamped
  EXPECT_EQ(c[1].r, 128);
  EXPECT_EQ(quantileRange({}).max, 1.0);
}

TEST(AttributeColors, NiceTicksAreRoundAndInside) {
  EXPECT_EQ(niceTicks({0, 9.131}), (std::vector<double>{0, 2, 4, 6, 8}));
  EXPECT_EQ(niceTicks({0.013, 0.26}), (std::vector<double>{0.05, 0.1, 0.15, 0.2, 0.25}));
  EXPECT_EQ(niceTicks({253.9, 257.6}), (std::vector<double>{254, 255, 256, 257}));
  EXPECT_EQ(niceTicks({-1, 1}), (std::vector<double>{-1, -0.5, 0, 0.5, 1}));
  EXPECT_TRUE(niceTicks({1, 1}).empty());
  EXPECT_TRUE(niceTicks({2, 1}).empty());
  for (const ValueRange& r : {ValueRange{0.0, 1e-6}, ValueRange{3.3, 47000.0}, ValueRange{-5.5, -5.1}}) {
    std::vector<double> t = niceTicks(r);
    EXPECT_GE(t.size(), 2u);
    EXPECT_LE(t.size(), 5u);
    for (double x : t) EXPECT_TRUE(x >= r.min && x <= r.max) << x;
  }
}

ViewerState& withCloud(ViewerState& s, geom::PointCloud c) {
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  EXPECT_TRUE(s.setCloud(std::move(c), geom::UpAxis::Z));
  return s;
}

geom::PointCloud column(int n) {
  geom::PointCloud c;
  for (int i = 0; i < n; ++i) c.positions.emplace_back(0.1 * std::cos(i), 0.1 * std::sin(i), 0.01 * i);
  return c;
}

TEST(ColorLegend, ModesOfferedFollowTheFilesAttributes) {
  geom::PointCloud c = column(10);
  EXPECT_EQ(availableColorModes(c).size(), 3u);
  EXPECT_EQ(nextColorMode(ColorMode::Plain, c), ColorMode::Height);  // wraps over what exists
  c.classification.assign(10, 2);
  c.classification[3] = 5;
  EXPECT_EQ(nextColorMode(ColorMode::Plain, c), ColorMode::Classification);
  EXPECT_EQ(nextColorMode(ColorMode::Classification, c), ColorMode::Height);
  EXPECT_FALSE(colorModeAvailable(ColorMode::Intensity, c));
  EXPECT_TRUE(attributeColors(c, ColorMode::Intensity).empty());
}

TEST(ColorLegend, LegendsMatchTheColouring) {
  geom::PointCloud c = column(100);
  c.classification.assign(100, 5);
  for (int i = 0; i < 10; ++i) c.classification[static_cast<std::size_t>(i)] = 2;
  c.intensity.resize(100);
  for (int i = 0; i < 100; ++i) c.intensity[static_cast<std::size_t>(i)] = static_cast<float>(i);
  ViewerState s;
  withCloud(s, c);
  Legend h = colorLegend(s);
  EXPECT_EQ(h.kind, Legend::Kind::Scale);
  EXPECT_DOUBLE_EQ(h.range.min, 0.0);
  EXPECT_DOUBLE_EQ(h.range.max, 0.99);  // height along z
  EXPECT_EQ(h.ramp.front(), render::viridis(0.0));
  EXPECT_EQ(h.ramp.back(), render::viridis(1.0));

  s.view().setColorMode(ColorMode::Classification);
  Legend cl = colorLegend(s);
  ASSERT_EQ(cl.kind, Legend::Kind::Classes);
  ASSERT_EQ(cl.classes.size(), 2u);
  EXPECT_EQ(cl.classes[0].code, 2);
  EXPECT_EQ(cl.classes[0].count, 10u);
  EXPECT_EQ(cl.classes[1].name, "high vegetation");
  EXPECT_EQ(s.scene().pointColors()[0], classificationColor(2));
  EXPECT_EQ(s.scene().pointColors()[50], classificationColor(5));

  s.view().setColorMode(ColorMode::Intensity);
  Legend in = colorLegend(s);
  EXPECT_NEAR(in.range.min, 1.0, 1.0);
  EXPECT_NEAR(in.range.max, 98.0, 1.0);
  EXPECT_EQ(s.scene().pointColors()[0], (Rgb{0, 0, 0}));  // below the 1 % value
  EXPECT_EQ(s.scene().pointColors()[99], (Rgb{255, 255, 255}));

  s.view().setColorMode(ColorMode::CircleDistance);
  Legend d = colorLegend(s);
  EXPECT_DOUBLE_EQ(d.range.min, 0.0);
  EXPECT_NEAR(d.range.max, s.options().distanceColorScale * s.bounds().diagonal(), 1e-12);

  s.view().setColorMode(ColorMode::FileColor);  // the cloud has none: plain, and the legend says so
  EXPECT_EQ(colorLegend(s).kind, Legend::Kind::None);
  EXPECT_NE(colorLegend(s).note.find("no rgb"), std::string::npos);
  EXPECT_EQ(s.scene().pointColors()[0], s.options().plainColor);
}

TEST(ColorLegend, ColourModeNamesParse) {
  EXPECT_EQ(parseColorMode("intensity"), ColorMode::Intensity);
  EXPECT_EQ(parseColorMode("RGB"), ColorMode::FileColor);
  EXPECT_EQ(parseColorMode("classification"), ColorMode::Classification);
  for (ColorMode m : {ColorMode::Intensity, ColorMode::FileColor, ColorMode::Classification})
    EXPECT_EQ(parseColorMode(toString(m)), m);
}

// ---- scale bar and gizmo ------------------------------------------------------------------------------

TEST(ViewOverlays, RoundLengths) {
  EXPECT_DOUBLE_EQ(roundLengthAtMost(1.0), 1.0);
  EXPECT_DOUBLE_EQ(roundLengthAtMost(1000.0), 1000.0);
  EXPECT_DOUBLE_EQ(roundLengthAtMost(0.37), 0.2);
  EXPECT_DOUBLE_EQ(roundLengthAtMost(7.9), 5.0);
  EXPECT_DOUBLE_EQ(roundLengthAtMost(19.99), 10.0);
  EXPECT_DOUBLE_EQ(roundLengthAtMost(0.0049), 0.002);
  EXPECT_EQ(roundLengthAtMost(0.0), 0.0);
  EXPECT_EQ(roundLengthAtMost(-3.0), 0.0);
  EXPECT_EQ(roundLengthAtMost(std::nan("")), 0.0);
}

TEST(ViewOverlays, ScaleBarAdaptsToZoom) {
  ScaleBar far = scaleBarFor(0.05, 160);  // 8 m fit in 160 px
  EXPECT_DOUBLE_EQ(far.length, 5.0);
  EXPECT_DOUBLE_EQ(far.pixels, 100.0);
  EXPECT_EQ(far.label, "5 m");
  ScaleBar near = scaleBarFor(0.001, 160);  // zoomed in: 16 cm fit
  EXPECT_DOUBLE_EQ(near.length, 0.1);
  EXPECT_EQ(near.label, "10 cm");
  ScaleBar dm = scaleBarFor(0.05, 160, 0.1);  // a cloud in decimetres: 80 cm fit
  EXPECT_NEAR(dm.length, 5.0, 1e-12);         // 5 units = 50 cm
  EXPECT_EQ(dm.label, "50 cm");
  EXPECT_FALSE(scaleBarFor(0.0, 160).valid());
  EXPECT_FALSE(scaleBarFor(std::nan(""), 160).valid());
  EXPECT_EQ(formatLength(0.002), "2 mm");
  EXPECT_EQ(formatLength(1500), "1.5 km");
  EXPECT_EQ(formatLength(0.92), "92 cm");
}

TEST(ViewOverlays, GizmoFollowsTheCamera) {
  geom::Camera cam = frontCamera();  // looking down -z, y up
  std::array<GizmoAxis, 3> g = axisGizmo(cam);
  EXPECT_EQ(g[2].axis, 2);  // z points at the viewer: drawn last
  EXPECT_NEAR(g[2].direction.norm(), 0.0, 1e-9);
  for (const GizmoAxis& a : g) {
    if (a.axis == 0) EXPECT_NEAR((a.direction - Vec2(1, 0)).norm(), 0.0, 1e-9);
    if (a.axis == 1) EXPECT_NEAR((a.direction - Vec2(0, -1)).norm(), 0.0, 1e-9);  // screen y is down
  }
  cam.view = geom::lookAt(Vec3(10, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 1));  // from +x, z up
  g = axisGizmo(cam);
  EXPECT_EQ(g[2].axis, 0);
  for (const GizmoAxis& a : g)
    if (a.axis == 2) EXPECT_NEAR((a.direction - Vec2(0, -1)).norm(), 0.0, 1e-9);
}

// ---- unsaved work and the key list ---------------------------------------------------------------------

TEST(UnsavedWork, AskedOfTheSketchFile) {
  test::TempDir dir;
  ViewerState s;
  withCloud(s, column(400));
  s.setSketchPath(dir / "t.sketch.json");
  EXPECT_FALSE(hasUnsavedWork(s));  // nothing sketched
  ASSERT_TRUE(s.addNodeAt(Vec2(400, 300)));
  EXPECT_TRUE(hasUnsavedWork(s));  // no file yet
  ASSERT_TRUE(s.saveSketch(dir / "t.sketch.json"));
  EXPECT_FALSE(hasUnsavedWork(s));
  ASSERT_TRUE(s.addNodeAt(Vec2(400, 200)));
  EXPECT_TRUE(hasUnsavedWork(s));
  ASSERT_TRUE(s.undo());  // back to what the file holds
  EXPECT_FALSE(hasUnsavedWork(s));
  test::writeText(dir / "t.sketch.json", "{ not json");
  EXPECT_TRUE(hasUnsavedWork(s));
  s.setSketchPath("");
  EXPECT_TRUE(hasUnsavedWork(s));
}

TEST(KeyHelp, TheHelpOverlaysTableListsTheWindowKeysAndEveryBoundKey) {
  // The overlay (F1) lists viewer::keyBindings(); the window's own keys are in it, grouped.
  std::set<std::string> groups, keys;
  for (const KeyBinding& k : keyBindings()) {
    EXPECT_FALSE(k.group.empty()) << k.keys;
    groups.insert(k.group);
    keys.insert(k.keys);
  }
  for (const char* g : {"Mouse", "Sketch", "Tools", "View", "File", "Help"}) EXPECT_TRUE(groups.count(g)) << g;
  for (const char* k : {"F1", "M", "Ctrl+O", "Ctrl+Shift+S", "Ctrl+E", "Ctrl+Q"}) EXPECT_TRUE(keys.count(k)) << k;
  // And the keys ViewerState binds are all listed.
  for (const char* key : {"delete", "ctrl+z", "ctrl+y", "ctrl+s", "escape", "f", "o", "1", "a", "w", "c", "l", "p"}) {
    bool listed = false;
    for (const KeyBinding& k : keyBindings()) listed |= k.keyName == key;
    EXPECT_TRUE(listed) << key;
  }
}

// ---- script verbs for the window ------------------------------------------------------------------------

ActionScript script(const std::string& text) {
  std::istringstream in(text);
  return parseActionScript(in, "s.json");
}

TEST(WindowScript, ParsesWindowVerbs) {
  ActionScript s = script(R"([{"menu": "open-cloud"}, {"dialog": "ok", "path": "data/t.xyz"}, {"pick": [10, 20]},
      {"menu": "recent", "value": 1}, "closeWindow", "prompt discard", {"showMenu": "File"},
      {"expectWindow": {"picks": 2, "distanceMin": 0.5}}, {"load": "x.json", "expectError": true}])");
  ASSERT_EQ(s.actions.size(), 9u);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(s.actions[i].kind, ScriptAction::Kind::Window) << i;
  EXPECT_EQ(s.actions[0].name, "menu");
  EXPECT_EQ(s.actions[0].text, "open-cloud");
  EXPECT_EQ(s.actions[1].path, fs::path("data/t.xyz"));
  EXPECT_EQ(s.actions[2].from, Vec2(10, 20));
  EXPECT_EQ(s.actions[3].value, 1.0);
  EXPECT_EQ(s.actions[4].name, "closeWindow");
  EXPECT_EQ(s.actions[5].text, "discard");
  EXPECT_EQ(s.actions[7].expect.size(), 2u);
  EXPECT_TRUE(s.actions[8].expectError);
  EXPECT_EQ(s.actions[8].kind, ScriptAction::Kind::Load);
  EXPECT_EQ(describe(s.actions[1]), "dialog ok data/t.xyz");
}

TEST(WindowScript, RejectsUnknownWindowNames) {
  for (const char* bad : {R"([{"menu": "open"}])", R"([{"menu": "recent"}])", R"([{"prompt": "yes"}])",
                          R"([{"expectWindow": {"nope": 1}}])", R"([{"pick": [1]}])", R"(["menu bogus"])",
                          R"([{"menu": "save", "expectError": 1}])"}) {
    EXPECT_THROW(script(bad), InputError) << bad;
  }
}

TEST(WindowScript, WindowVerbsNeedAWindowAndExpectErrorInvertsTheOutcome) {
  ViewerState state;
  withCloud(state, column(400));
  ActionScript s = script(R"([{"menu": "quit"}, {"load": "/nonexistent/x.json", "expectError": true},
      {"view": "front", "expectError": true}])");
  ScriptReport r = runActionScript(state, s);
  ASSERT_EQ(r.failures.size(), 2u);
  EXPECT_NE(r.failures[0].find("needs a window"), std::string::npos) << r.failures[0];
  EXPECT_NE(r.failures[1].find("action 2"), std::string::npos) << r.failures[1];  // did not fail
  std::vector<std::string> seen;
  ScriptHooks hooks;
  hooks.window = [&](const ScriptAction& a) {
    seen.push_back(a.name + ":" + a.text);
    return a.text == "cancel" ? std::string("no prompt is open") : std::string();
  };
  ScriptReport r2 = runActionScript(state, script(R"([{"menu": "quit"}, {"prompt": "cancel"},
      {"prompt": "cancel", "expectError": true}])"),
                                    hooks);
  EXPECT_EQ(seen, (std::vector<std::string>{"menu:quit", "prompt:cancel", "prompt:cancel"}));
  ASSERT_EQ(r2.failures.size(), 1u);
  EXPECT_NE(r2.failures[0].find("no prompt is open"), std::string::npos);
}

}  // namespace
}  // namespace treesketch::viewer

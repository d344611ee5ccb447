// The playlist: the example plays as written, defaults, and every mistake's exact message.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include "playback/playlist.h"
#include "playback/timeline.h"

namespace fs = std::filesystem;
using namespace playback;

namespace {

const std::string test_dir = PLAYBACK_TEST_DIR;
// Does not exist, so no symlink resolution changes the paths in the messages.
const std::string list = "/content/show/list.toml";

std::string real(const fs::path& p) {
  return fs::weakly_canonical(p).string();
}

// What the player's render settings would accept, as the app will pass it in.
bool validate(std::string_view key, std::string_view value, std::string& error) {
  if (key == "estimator") {
    if (value == "sphere" || value == "hemisphere" || value == "horizon") return true;
    error = "expected one of sphere, hemisphere, horizon";
    return false;
  }
  if (key == "samples") {
    const int n = std::atoi(std::string(value).c_str());
    if (n >= 1 && n <= 64 && std::to_string(n) == value) return true;
    error = "expected an integer in 1..64";
    return false;
  }
  if (key == "radius") return true;
  if (key == "blur") {
    if (value == "on" || value == "off") return true;
    error = "expected on or off";
    return false;
  }
  error = "expected a render setting (estimator, samples, radius, blur)";
  return false;
}

ParseOptions options() {
  ParseOptions o;
  o.validate_setting = validate;
  return o;
}

Playlist parse_ok(const std::string& text, const ParseOptions& o = options()) {
  Playlist pl;
  std::string error;
  EXPECT_TRUE(parse_playlist(text, list, o, pl, error)) << error;
  return pl;
}

}  // namespace

TEST(Playlist, ExampleFilePlaysAsWritten) {
  Playlist pl;
  std::string error;
  ASSERT_TRUE(load_playlist(test_dir + "/example.toml", options(), pl, error)) << error;
  EXPECT_EQ(pl.source, test_dir + "/example.toml");
  EXPECT_TRUE(pl.loop);
  EXPECT_FALSE(pl.shuffle);
  EXPECT_EQ(pl.seed, 1u);
  EXPECT_EQ(pl.fade_s, 0.5);
  EXPECT_EQ(pl.schedule, Schedule::sequential);
  ASSERT_EQ(pl.items.size(), 1u);
  const Item& it = pl.items[0];
  EXPECT_EQ(it.scene, real(test_dir + "/models/bunny.glb"));
  EXPECT_EQ(it.duration_s, 8.0);
  EXPECT_EQ(it.camera.motion, Motion::turntable);
  EXPECT_EQ(it.camera.period_s, 20.0);
  EXPECT_EQ(it.camera.elevation_deg, 15.0);
  EXPECT_EQ(it.camera.distance, 1.1);
  EXPECT_EQ(it.camera.azimuth_deg, 30.0);
  EXPECT_EQ(it.camera.fov_deg, 45.0);
  EXPECT_TRUE(it.camera.keys.empty());
  EXPECT_EQ(it.settings, (std::vector<Setting>{{"estimator", "horizon"}, {"samples", "32"}}));
  EXPECT_FALSE(it.has_background);
  EXPECT_EQ(it.display, "");
  EXPECT_EQ(it.line, 2);
}

TEST(Playlist, TheScenesOwnCameraByIndex) {
  const Playlist pl = parse_ok(
      "[[item]]\nscene = \"a.glb\"\ncamera = { motion = \"file\", index = 2 }\n"
      "[[item]]\nscene = \"b.glb\"\ncamera = { motion = \"file\" }\n"
      "[[item]]\nscene = \"c.glb\"\ncamera = { motion = \"file\", index = 0 }\n"
      "[[item]]\nscene = \"d.glb\"\ncamera = { motion = \"file\", index = 1000000 }\n");
  EXPECT_EQ(pl.items.at(0).camera.motion, Motion::file);
  EXPECT_EQ(pl.items[0].camera.index, 2);
  EXPECT_EQ(camera_at(pl.items[0].camera, 3.0).file_index, 2);
  EXPECT_EQ(pl.items.at(1).camera.index, 0);  // the first camera when none is named
  EXPECT_EQ(camera_at(pl.items[1].camera, 0.0).file_index, 0);
  EXPECT_EQ(pl.items.at(2).camera.index, 0);
  EXPECT_EQ(pl.items.at(3).camera.index, 1000000) << "the largest index taken";
  CameraPath turntable;
  EXPECT_EQ(camera_at(turntable, 1.0).file_index, -1);
}

TEST(Playlist, Defaults) {
  const Playlist pl = parse_ok("[[item]]\nscene = \"a.glb\"\n");
  EXPECT_EQ(pl.source, list);
  EXPECT_TRUE(pl.loop);
  EXPECT_FALSE(pl.shuffle);
  EXPECT_EQ(pl.seed, 1u);
  EXPECT_EQ(pl.fade_s, 0.5);
  EXPECT_EQ(pl.schedule, Schedule::sequential);
  ASSERT_EQ(pl.items.size(), 1u);
  const Item& it = pl.items[0];
  EXPECT_EQ(it.scene, "/content/show/a.glb");
  EXPECT_EQ(it.duration_s, 10.0);
  EXPECT_EQ(it.camera.motion, Motion::turntable);
  EXPECT_EQ(it.camera.period_s, 20.0);
  EXPECT_EQ(it.camera.elevation_deg, 20.0);
  EXPECT_EQ(it.camera.distance, 1.0);
  EXPECT_EQ(it.camera.azimuth_deg, 30.0);
  EXPECT_EQ(it.camera.fov_deg, 45.0);
  EXPECT_TRUE(it.settings.empty());
  EXPECT_FALSE(it.has_background);
  EXPECT_EQ(it.display, "");
  EXPECT_EQ(it.line, 1);
}

TEST(Playlist, BackgroundTakesBothEndsOfItsRange) {
  Playlist pl;
  std::string error;
  ASSERT_TRUE(parse_playlist("[[item]]\nscene = \"a.glb\"\nbackground = [0, 0.5, 1]\n", list, options(), pl, error)) << error;
  EXPECT_EQ(pl.items.at(0).background, glm::vec3(0.0f, 0.5f, 1.0f));
}

// "#rrggbb" as web colours are written: each pair its own channel, either case.
TEST(Playlist, AHexColourSetsEachOfItsThreeChannels) {
  for (const auto& [text, want] :
       {std::pair{"#1a2b3c", glm::vec3(0x1a, 0x2b, 0x3c) / 255.0f}, std::pair{"#FFFEFD", glm::vec3(255, 254, 253) / 255.0f}}) {
    Playlist pl;
    std::string error;
    ASSERT_TRUE(
        parse_playlist(std::string("[[item]]\nscene = \"a.glb\"\nbackground = \"") + text + "\"\n", list, options(), pl, error))
        << error;
    EXPECT_EQ(pl.items.at(0).background, want) << text;
  }
}

// The camera's ranges are taken to their ends: elevation [-89, 89] closed, fov (1, 170) open, and a
// turntable period may be any positive time (a turn in half a second).
TEST(Playlist, CameraValuesAtTheEndsOfTheirRangesAreTaken) {
  const Playlist pl = parse_ok(
      "[[item]]\nscene = \"a.glb\"\ncamera = { motion = \"still\", elevation = -89, fov = 169.9 }\n"
      "[[item]]\nscene = \"b.glb\"\ncamera = { motion = \"still\", elevation = 89, fov = 1.1 }\n"
      "[[item]]\nscene = \"c.glb\"\ncamera = { period = 0.5 }\n");
  ASSERT_EQ(pl.items.size(), 3u);
  EXPECT_EQ(pl.items[0].camera.elevation_deg, -89.0);
  EXPECT_EQ(pl.items[0].camera.fov_deg, 169.9);
  EXPECT_EQ(pl.items[1].camera.elevation_deg, 89.0);
  EXPECT_EQ(pl.items[1].camera.fov_deg, 1.1);
  EXPECT_EQ(pl.items[2].camera.period_s, 0.5);
}

TEST(Playlist, SeedZeroIsASeedLikeAnyOther) {
  Playlist pl;
  std::string error;
  ASSERT_TRUE(
      parse_playlist("shuffle = true\nseed = 0\n"
                     "[[item]]\nscene = \"a.glb\"\n",
                     list, options(), pl, error))
      << error;
  EXPECT_EQ(pl.seed, 0u);
}

TEST(Playlist, EveryKeySet) {
  Playlist pl;
  std::string error;
  ASSERT_TRUE(load_playlist(test_dir + "/full.toml", options(), pl, error)) << error;
  EXPECT_FALSE(pl.loop);
  EXPECT_TRUE(pl.shuffle);
  EXPECT_EQ(pl.seed, 42u);
  EXPECT_EQ(pl.fade_s, 1.25);
  EXPECT_EQ(pl.schedule, Schedule::wallclock);
  ASSERT_EQ(pl.items.size(), 2u);

  const Item& a = pl.items[0];
  EXPECT_EQ(a.line, 8);
  EXPECT_EQ(a.scene, "builtin:cube");
  EXPECT_EQ(a.duration_s, 5.0);
  EXPECT_TRUE(a.has_background);
  EXPECT_EQ(a.background, glm::vec3(0.25f, 0.5f, 1.0f));
  EXPECT_EQ(a.display, real(test_dir + "/displays/looking_glass.toml"));
  EXPECT_EQ(a.camera.motion, Motion::still);
  EXPECT_EQ(a.camera.azimuth_deg, -45.0);
  EXPECT_EQ(a.camera.elevation_deg, -10.0);
  EXPECT_EQ(a.camera.distance, 2.0);
  EXPECT_EQ(a.camera.fov_deg, 60.0);

  const Item& b = pl.items[1];
  EXPECT_EQ(b.line, 15);
  EXPECT_EQ(b.scene, real(test_dir + "/models/helmet.gltf"));
  EXPECT_EQ(b.duration_s, 10.0);
  EXPECT_TRUE(b.has_background);
  EXPECT_EQ(b.background, glm::vec3(1.0f, 128 / 255.0f, 0.0f));
  EXPECT_EQ(b.camera.motion, Motion::orbit);
  ASSERT_EQ(b.camera.keys.size(), 3u);
  // Keys that leave out a value take the camera table's (azimuth 10, elevation 20, distance 1).
  const double want[3][4] = {{0, 0, 10, 1.2}, {4, 180, 20, 1.0}, {9.5, 360, -5, 0.8}};
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(b.camera.keys[i].t, want[i][0]);
    EXPECT_EQ(b.camera.keys[i].azimuth_deg, want[i][1]);
    EXPECT_EQ(b.camera.keys[i].elevation_deg, want[i][2]);
    EXPECT_EQ(b.camera.keys[i].distance, want[i][3]);
  }
  // In file order, as the command line would take them.
  EXPECT_EQ(b.settings, (std::vector<Setting>{{"estimator", "sphere"}, {"samples", "16"}, {"radius", "0.25"}, {"blur", "off"}}));
}

TEST(Playlist, SettingsTextIsWhatTheCommandLineTakes) {
  const Playlist pl = parse_ok(
      "[[item]]\nscene = \"a.glb\"\nao = { a = true, b = 0.1, c = 1e300, d = -7, e = 2.0, f = \"x y\" }\n", ParseOptions{});
  EXPECT_EQ(pl.items[0].settings,
            (std::vector<Setting>{{"a", "on"}, {"b", "0.1"}, {"c", "1e+300"}, {"d", "-7"}, {"e", "2"}, {"f", "x y"}}));
}

TEST(Playlist, BuiltinScenesPassThroughAndAbsolutePathsInsideTheRootAreKept) {
  const Playlist pl = parse_ok(
      "[[item]]\nscene = \"builtin:../../sponza\"\n[[item]]\nscene = \"/content/show/sub/../b.glb\"\n"
      "[[item]]\nscene = \"./c/./d.glb\"\n");
  EXPECT_EQ(pl.items[0].scene, "builtin:../../sponza");
  EXPECT_EQ(pl.items[1].scene, "/content/show/b.glb");
  EXPECT_EQ(pl.items[2].scene, "/content/show/c/d.glb");
  EXPECT_EQ(pl.items[1].line, 3);
  EXPECT_EQ(pl.items[2].line, 5);
}

TEST(Playlist, ContentRootOptionWidensWhereScenesMayBe) {
  ParseOptions o = options();
  o.content_root = "/content";
  const Playlist pl = parse_ok("[[item]]\nscene = \"../other/a.glb\"\n", o);
  EXPECT_EQ(pl.items[0].scene, "/content/other/a.glb");
}

TEST(Playlist, SceneFilesNeedNotExist) {
  Playlist pl;
  std::string error;
  EXPECT_TRUE(parse_playlist("[[item]]\nscene = \"missing.glb\"\n", test_dir + "/x.toml", options(), pl, error)) << error;
  EXPECT_EQ(pl.items[0].scene, real(test_dir + "/missing.glb"));
}

TEST(Playlist, AnimationKeys) {
  const Playlist pl = parse_ok(
      "[[item]]\nscene = \"a.glb\"\n"
      "[[item]]\nscene = \"a.glb\"\nanimation = \"Walk\"\nanimation_speed = 0.5\n"
      "[[item]]\nscene = \"a.glb\"\nanimation = 2\n"
      "[[item]]\nscene = \"a.glb\"\nanimation = \"none\"\n"
      "[[item]]\nscene = \"a.glb\"\nanimation = 0\n");
  ASSERT_EQ(pl.items.size(), 5u);
  EXPECT_EQ(pl.items[0].animation, "all");  // the default: every animation, as authored
  EXPECT_EQ(pl.items[0].animation_speed, 1.0);
  EXPECT_EQ(pl.items[1].animation, "Walk");
  EXPECT_EQ(pl.items[1].animation_speed, 0.5);
  EXPECT_EQ(pl.items[2].animation, "2");
  EXPECT_EQ(pl.items[3].animation, "none");
  EXPECT_EQ(pl.items[4].animation, "0") << "the first animation, by index";
}

TEST(Playlist, FailureLeavesOutputUnchanged) {
  Playlist pl = playlist_from_scenes({"keep.glb"}, 3, 4);
  std::string error;
  EXPECT_FALSE(parse_playlist("loop = 3\n[[item]]\nscene = \"a.glb\"\n", list, options(), pl, error));
  ASSERT_EQ(pl.items.size(), 1u);
  EXPECT_EQ(pl.items[0].scene, "keep.glb");
}

struct ErrorCase {
  const char* name;
  const char* text;
  const char* error;  // after "/content/show/list.toml:"
};

void PrintTo(const ErrorCase& c, std::ostream* os) {
  *os << c.name;
}

class PlaylistError : public testing::TestWithParam<ErrorCase> {};

TEST_P(PlaylistError, SaysWhereWhatAndWhatWasExpected) {
  Playlist pl;
  std::string error;
  EXPECT_FALSE(parse_playlist(GetParam().text, list, options(), pl, error));
  EXPECT_EQ(error, list + ":" + GetParam().error);
}

#define ITEM "[[item]]\nscene = \"a.glb\"\n"

const ErrorCase error_cases[] = {
    // Top level.
    {"LoopNotBool", "loop = 1\n" ITEM, "1:8: loop: expected true or false, got an integer"},
    {"ShuffleNotBool", "shuffle = \"yes\"\n" ITEM, "1:11: shuffle: expected true or false, got a string"},
    {"SeedNegative", "seed = -3\n" ITEM, "1:8: seed: expected an integer >= 0, got -3"},
    {"SeedFloat", "seed = 1.5\n" ITEM, "1:8: seed: expected an integer >= 0, got a floating-point number"},
    {"FadeNegative", "fade = -1.0\n" ITEM, "1:8: fade: expected a number of seconds >= 0, got -1"},
    {"FadeString", "fade = \"1s\"\n" ITEM, "1:8: fade: expected a number of seconds >= 0, got a string"},
    {"ScheduleUnknown", "schedule = \"random\"\n" ITEM, "1:12: schedule: expected one of sequential, wallclock, got \"random\""},
    {"UnknownTopLevelKey", "loop = true\nspeed = 2\n" ITEM,
     "2:1: speed: expected one of loop, shuffle, seed, fade, schedule, item, got an unknown key"},
    {"NoItems", "loop = true\n", "1:1: item: expected at least one [[item]] table, got nothing"},
    {"EmptyItemList", "item = []\n", "1:8: item: expected at least one [[item]] table, got an empty array"},
    {"ItemIsATable", "[item]\nscene = \"a.glb\"\n", "1:1: item: expected at least one [[item]] table, got a table"},
    {"ItemsNotTables", "item = [1, 2]\n", "1:8: item: expected at least one [[item]] table, got an array of non-tables"},
    // Items.
    {"MissingScene", "loop = true\n\n[[item]]\nduration = 3\n",
     "3:1: item[0].scene: expected a path or builtin:NAME, got nothing"},
    {"SceneNotString", "[[item]]\nscene = 3\n", "2:9: item[0].scene: expected a path or builtin:NAME, got an integer"},
    {"AnimationNegative", ITEM "animation = -1\n",
     "3:13: item[0].animation: expected \"all\", \"none\", a name or an index >= 0, got -1"},
    {"AnimationTable", ITEM "animation = {}\n",
     "3:13: item[0].animation: expected \"all\", \"none\", a name or an index >= 0, got a table"},
    {"AnimationSpeedNegative", ITEM "animation_speed = -2\n",
     "3:19: item[0].animation_speed: expected a number >= 0 (1: as authored, 0: held at the start), got -2"},
    {"SceneEmpty", "[[item]]\nscene = \"\"\n", "2:9: item[0].scene: expected a path or builtin:NAME, got an empty string"},
    {"BuiltinWithoutName", "[[item]]\nscene = \"builtin:\"\n",
     "2:9: item[0].scene: expected a name after builtin:, got \"builtin:\""},
    {"UnknownItemKey", ITEM "sound = \"x.ogg\"\n",
     "3:1: item[0].sound: expected one of scene, duration, camera, ao, background, display, environment, animation, "
     "animation_speed, got an unknown key"},
    {"DurationZero", ITEM "duration = 0\n", "3:12: item[0].duration: expected a number of seconds > 0, got 0"},
    {"DurationString", ITEM "duration = \"8\"\n", "3:12: item[0].duration: expected a number of seconds > 0, got a string"},
    {"DurationInfinite", ITEM "duration = inf\n", "3:12: item[0].duration: expected a number of seconds > 0, got inf"},
    // TOML's own date and time values are named as such.
    {"DurationTime", ITEM "duration = 07:32:00\n", "3:12: item[0].duration: expected a number of seconds > 0, got a time"},
    {"DurationDate", ITEM "duration = 1979-05-27\n", "3:12: item[0].duration: expected a number of seconds > 0, got a date"},
    {"DurationDateTime", ITEM "duration = 1979-05-27T07:32:00Z\n",
     "3:12: item[0].duration: expected a number of seconds > 0, got a date-time"},
    {"SecondItemNamed", ITEM "[[item]]\nscene = \"b.glb\"\nduration = -2\n",
     "5:12: item[1].duration: expected a number of seconds > 0, got -2"},
    // Paths.
    {"SceneEscapesByDotDot", "[[item]]\nscene = \"../other/a.glb\"\n",
     "2:9: item[0].scene: expected a path inside the content root /content/show, got \"../other/a.glb\" "
     "(resolves to \"/content/other/a.glb\")"},
    {"SceneEscapesByAbsolutePath", "[[item]]\nscene = \"/srv/a.glb\"\n",
     "2:9: item[0].scene: expected a path inside the content root /content/show, got \"/srv/a.glb\" "
     "(resolves to \"/srv/a.glb\")"},
    {"SceneEscapesAfterGoingIn", "[[item]]\nscene = \"models/../../show2/a.glb\"\n",
     "2:9: item[0].scene: expected a path inside the content root /content/show, got \"models/../../show2/a.glb\" "
     "(resolves to \"/content/show2/a.glb\")"},
    {"DisplayEscapes", ITEM "display = \"../../d.toml\"\n",
     "3:11: item[0].display: expected a path inside the content root /content/show, got \"../../d.toml\" "
     "(resolves to \"/d.toml\")"},
    {"DisplayNotBuiltin", ITEM "display = 4\n", "3:11: item[0].display: expected a path, got an integer"},
    // Background.
    {"BackgroundTwoNumbers", ITEM "background = [0.5, 0.5]\n",
     "3:14: item[0].background: expected an array of 3 numbers in [0, 1] or a \"#rrggbb\" string, got an array of 2"},
    {"BackgroundOutOfRange", ITEM "background = [0.5, 1.5, 0]\n",
     "3:20: item[0].background[1]: expected a number in [0, 1], got 1.5"},
    {"BackgroundNotNumber", ITEM "background = [0.5, \"red\", 0]\n",
     "3:20: item[0].background[1]: expected a number in [0, 1], got a string"},
    {"BackgroundBadHex", ITEM "background = \"#12345g\"\n",
     "3:14: item[0].background: expected an array of 3 numbers in [0, 1] or a \"#rrggbb\" string, got \"#12345g\""},
    {"BackgroundShortHex", ITEM "background = \"#fff\"\n",
     "3:14: item[0].background: expected an array of 3 numbers in [0, 1] or a \"#rrggbb\" string, got \"#fff\""},
    {"BackgroundInteger", ITEM "background = 3\n",
     "3:14: item[0].background: expected an array of 3 numbers in [0, 1] or a \"#rrggbb\" string, got an integer"},
    // Camera.
    {"CameraNotTable", ITEM "camera = \"spin\"\n", "3:10: item[0].camera: expected a table, got a string"},
    {"UnknownCameraKey", ITEM "camera = { motion = \"still\", speed = 3 }\n",
     "3:30: item[0].camera.speed: expected one of motion, period, elevation, distance, azimuth, fov, keys, index, got an unknown "
     "key"},
    {"UnknownCameraKeyInSubTable", ITEM "[item.camera]\nmotion = \"still\"\nroll = 5\n",
     "5:1: item[0].camera.roll: expected one of motion, period, elevation, distance, azimuth, fov, keys, index, got an unknown "
     "key"},
    {"MotionUnknown", ITEM "camera = { motion = \"spin\" }\n",
     "3:21: item[0].camera.motion: expected one of still, turntable, orbit, file, got \"spin\""},
    {"MotionNotString", ITEM "camera = { motion = 1 }\n",
     "3:21: item[0].camera.motion: expected one of still, turntable, orbit, file, got an integer"},
    {"PeriodNegative", ITEM "camera = { period = -20 }\n",
     "3:21: item[0].camera.period: expected seconds per turn > 0 (a negative period is not supported), got -20"},
    {"PeriodZero", ITEM "camera = { period = 0 }\n", "3:21: item[0].camera.period: expected seconds per turn > 0, got 0"},
    {"ElevationTooHigh", ITEM "camera = { elevation = 90 }\n",
     "3:24: item[0].camera.elevation: expected degrees in [-89, 89], got 90"},
    {"ElevationTooLow", ITEM "camera = { elevation = -89.5 }\n",
     "3:24: item[0].camera.elevation: expected degrees in [-89, 89], got -89.5"},
    {"DistanceZero", ITEM "camera = { distance = 0 }\n",
     "3:23: item[0].camera.distance: expected a multiple of the fitting distance > 0, got 0"},
    {"FovTooWide", ITEM "camera = { fov = 170 }\n", "3:18: item[0].camera.fov: expected degrees in (1, 170), got 170"},
    {"FovTooNarrow", ITEM "camera = { fov = 1.0 }\n", "3:18: item[0].camera.fov: expected degrees in (1, 170), got 1"},
    {"AzimuthNan", ITEM "camera = { azimuth = nan }\n", "3:22: item[0].camera.azimuth: expected degrees, got nan"},
    // Orbits.
    {"OrbitOneKey", ITEM "camera = { motion = \"orbit\", keys = [ { t = 0.0 } ] }\n",
     "3:37: item[0].camera.keys: expected at least 2 keys, got an array of 1"},
    {"OrbitNoKeys", ITEM "camera = { motion = \"orbit\" }\n",
     "3:10: item[0].camera.keys: expected at least 2 keys for motion \"orbit\", got nothing"},
    {"OrbitKeysNotTables", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [1, 2]\n",
     "5:8: item[0].camera.keys: expected an array of at least 2 tables { t = ..., azimuth = ..., elevation = ..., "
     "distance = ... }, got an array of non-tables"},
    {"OrbitTNotIncreasing",
     ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [\n  { t = 0.0, azimuth = 0.0 },\n"
          "  { t = 3.0, azimuth = 90.0 },\n  { t = 3.0, azimuth = 180.0 },\n]\n",
     "8:9: item[0].camera.keys[2].t: expected a time after the previous key's 3, got 3"},
    {"OrbitTDecreasing", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [ { t = 0 }, { t = 5 }, { t = 2.5 } ]\n",
     "5:38: item[0].camera.keys[2].t: expected a time after the previous key's 5, got 2.5"},
    {"OrbitFirstTNotZero", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [ { t = 1.0 }, { t = 2.0 } ]\n",
     "5:16: item[0].camera.keys[0].t: expected 0 (the first key is the item's start), got 1"},
    {"OrbitTBeyondItem", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [ { t = 0 }, { t = 12 } ]\n",
     "5:27: item[0].camera.keys[1].t: expected a time within the item's 10 s, got 12"},
    {"OrbitKeyDistanceZero", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [ { t = 0 }, { t = 1, distance = 0.0 } ]\n",
     "5:41: item[0].camera.keys[1].distance: expected a multiple of the fitting distance > 0, got 0"},
    {"OrbitKeyWithoutT", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [ { azimuth = 3 }, { t = 1 } ]\n",
     "5:10: item[0].camera.keys[0].t: expected a time in seconds, got nothing"},
    {"OrbitKeyUnknownKey", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [ { t = 0, roll = 3 }, { t = 1 } ]\n",
     "5:19: item[0].camera.keys[0].roll: expected one of t, azimuth, elevation, distance, got an unknown key"},
    {"OrbitKeyElevation", ITEM "[item.camera]\nmotion = \"orbit\"\nkeys = [ { t = 0, elevation = 95 }, { t = 1 } ]\n",
     "5:31: item[0].camera.keys[0].elevation: expected degrees in [-89, 89], got 95"},
    {"KeysWithoutOrbit", ITEM "camera = { keys = [] }\n",
     "3:19: item[0].camera.keys: expected keys only with motion = \"orbit\", got an empty array"},
    // The scene's own cameras.
    {"IndexWithoutFile", ITEM "camera = { index = 1 }\n",
     "3:20: item[0].camera.index: expected index only with motion = \"file\", got 1"},
    {"IndexNegative", ITEM "camera = { motion = \"file\", index = -1 }\n",
     "3:37: item[0].camera.index: expected a camera index of the scene, 0 or more, got -1"},
    {"IndexFraction", ITEM "camera = { motion = \"file\", index = 1.5 }\n",
     "3:37: item[0].camera.index: expected a camera index of the scene, 0 or more, got 1.5"},
    {"IndexBeyondAMillion", ITEM "camera = { motion = \"file\", index = 1000001 }\n",
     "3:37: item[0].camera.index: expected a camera index of the scene, 0 or more, got 1000001"},
    // Render settings.
    {"AoNotTable", ITEM "ao = 3\n", "3:6: item[0].ao: expected a table of render settings, got an integer"},
    {"AoUnknownKey", ITEM "ao = { estimator = \"horizon\", bogus = 1 }\n",
     "3:39: item[0].ao.bogus: expected a render setting (estimator, samples, radius, blur), got 1"},
    {"AoValueRejected", ITEM "ao = { estimator = \"cone\" }\n",
     "3:20: item[0].ao.estimator: expected one of sphere, hemisphere, horizon, got \"cone\""},
    {"AoNumberRejected", ITEM "ao = { samples = 100 }\n", "3:18: item[0].ao.samples: expected an integer in 1..64, got 100"},
    {"AoBoolRejected", ITEM "[item.ao]\nsamples = 8\nblur = \"maybe\"\n",
     "5:8: item[0].ao.blur: expected on or off, got \"maybe\""},
    {"AoNested", ITEM "ao = { blur = { radius = 2 } }\n",
     "3:15: item[0].ao.blur: expected a string, integer, float or boolean, got a table"},
    {"AoArray", ITEM "ao = { radius = [1, 2] }\n",
     "3:17: item[0].ao.radius: expected a string, integer, float or boolean, got an array"},
    // Messages stay on one line whatever the strings hold.
    {"ControlCharactersEscaped", "[[item]]\nscene = \"a\\nb\"\ncamera = { motion = \"a\\\"\\tb\" }\n",
     "3:21: item[0].camera.motion: expected one of still, turntable, orbit, file, got \"a\\\"\\tb\""},
    {"OtherControlCharactersAsHex", ITEM "camera = { motion = \"a\\u0001b\\u007f\" }\n",
     "3:21: item[0].camera.motion: expected one of still, turntable, orbit, file, got \"a\\x01b\\x7f\""},
    {"SpacesAndPrintableCharactersAsTheyAre", ITEM "camera = { motion = \"a b~\" }\n",
     "3:21: item[0].camera.motion: expected one of still, turntable, orbit, file, got \"a b~\""},
    // TOML syntax: toml++'s own words.
    {"SyntaxUnterminatedString", "loop = true\n[[item]]\nscene = \"a.glb\n",
     "3:15: Error while parsing string: unescaped control characters other than TAB (U+0009) are explicitly prohibited"},
    {"SyntaxDuplicateKey", "loop = true\nloop = false\n" ITEM,
     "2:8: Error while parsing key-value pair: cannot redefine existing boolean 'loop'"},
};

INSTANTIATE_TEST_SUITE_P(Playlist, PlaylistError, testing::ValuesIn(error_cases),
                         [](const testing::TestParamInfo<ErrorCase>& p) { return std::string(p.param.name); });

TEST(Playlist, ValidatorWithoutWordsStillSaysSomething) {
  ParseOptions o;
  o.validate_setting = [](std::string_view, std::string_view, std::string&) { return false; };
  Playlist pl;
  std::string error;
  EXPECT_FALSE(parse_playlist(ITEM "ao = { samples = 3 }\n", list, o, pl, error));
  EXPECT_EQ(error, list + ":3:18: item[0].ao.samples: expected a valid value, got 3");
}

TEST(Playlist, ValidatorSeesKeyAndText) {
  std::vector<std::pair<std::string, std::string>> seen;
  ParseOptions o;
  o.validate_setting = [&](std::string_view k, std::string_view v, std::string&) {
    seen.emplace_back(k, v);
    return true;
  };
  parse_ok(ITEM "ao = { blur = true, radius = 0.5 }\n", o);
  EXPECT_EQ(seen, (std::vector<std::pair<std::string, std::string>>{{"blur", "on"}, {"radius", "0.5"}}));
}

TEST(Playlist, SymlinkOutOfTheRootIsCaught) {
  const fs::path base = fs::path(testing::TempDir()) / ("playback_symlink_" + std::to_string(::getpid()));
  fs::remove_all(base);
  fs::create_directories(base / "show" / "models");
  fs::create_directories(base / "outside");
  std::ofstream(base / "outside" / "real.glb") << "x";
  std::ofstream(base / "show" / "models" / "inside.glb") << "x";
  fs::create_directory_symlink(base / "outside", base / "show" / "link");
  fs::create_directory_symlink(base / "show" / "models", base / "show" / "models_link");
  const std::string file = (base / "show" / "list.toml").string();

  Playlist pl;
  std::string error;
  EXPECT_FALSE(parse_playlist("[[item]]\nscene = \"link/real.glb\"\n", file, options(), pl, error));
  const std::string root = real(base / "show");
  EXPECT_EQ(error, file + ":2:9: item[0].scene: expected a path inside the content root " + root +
                       ", got \"link/real.glb\" (resolves to \"" + real(base / "outside" / "real.glb") + "\")");
  // A missing file behind the link is resolved through the link all the same.
  EXPECT_FALSE(parse_playlist("[[item]]\nscene = \"link/none.glb\"\n", file, options(), pl, error));

  // A link that stays inside is fine, and stored resolved.
  ASSERT_TRUE(parse_playlist("[[item]]\nscene = \"models_link/inside.glb\"\n", file, options(), pl, error)) << error;
  EXPECT_EQ(pl.items[0].scene, real(base / "show" / "models" / "inside.glb"));
  fs::remove_all(base);
}

TEST(Playlist, MissingFile) {
  Playlist pl;
  std::string error;
  EXPECT_FALSE(load_playlist("/nonexistent/list.toml", options(), pl, error));
  EXPECT_EQ(error, "/nonexistent/list.toml: cannot open the playlist (No such file or directory)");
}

TEST(Playlist, AFileOf64MiBIsReadAndOneByteMoreIsRefused) {
  const std::string path = testing::TempDir() + "playlist_size_limit_" + std::to_string(getpid()) + ".toml";
  for (const std::size_t size : {kMaxPlaylistBytes, kMaxPlaylistBytes + 1}) {
    SCOPED_TRACE(size);
    std::filesystem::resize_file((std::ofstream(path), path), size);  // a sparse file of NUL bytes
    Playlist pl;
    std::string error;
    EXPECT_FALSE(load_playlist(path, options(), pl, error));
    if (size == kMaxPlaylistBytes)  // read, then refused by the TOML parser
      EXPECT_EQ(error.find("at most"), std::string::npos) << error;
    else
      EXPECT_EQ(error, path + ": the playlist is 64.0 MiB (67108865 bytes); at most 64.0 MiB (67108864 bytes) is read");
  }
  std::filesystem::remove(path);
}

TEST(Playlist, DirectoryIsNotAPlaylist) {
  Playlist pl;
  std::string error;
  EXPECT_FALSE(load_playlist(test_dir, options(), pl, error));
  EXPECT_EQ(error, test_dir + ": the playlist is a folder, not a regular file");
}

TEST(Playlist, SyntaxErrorInAFileNamesTheFile) {
  const fs::path file = fs::path(testing::TempDir()) / ("playback_syntax_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(file) << "loop = tru\n";
  Playlist pl;
  std::string error;
  EXPECT_FALSE(load_playlist(file.string(), options(), pl, error));
  EXPECT_EQ(error.rfind(file.string() + ":1:", 0), 0u) << error;
  fs::remove(file);
}

TEST(Playlist, FromScenes) {
  const Playlist pl = playlist_from_scenes({"models/a.glb", "builtin:cube"}, 7.5, 12);
  EXPECT_EQ(pl.source, "command line");
  EXPECT_TRUE(pl.loop);
  EXPECT_FALSE(pl.shuffle);
  EXPECT_EQ(pl.fade_s, 0.5);
  EXPECT_EQ(pl.schedule, Schedule::sequential);
  ASSERT_EQ(pl.items.size(), 2u);
  EXPECT_EQ(pl.items[0].scene, "models/a.glb");
  EXPECT_EQ(pl.items[1].scene, "builtin:cube");
  for (const Item& it : pl.items) {
    EXPECT_EQ(it.duration_s, 7.5);
    EXPECT_EQ(it.camera.motion, Motion::turntable);
    EXPECT_EQ(it.camera.period_s, 12.0);
    EXPECT_EQ(it.camera.azimuth_deg, 30.0);
    EXPECT_TRUE(it.settings.empty());
  }
}

TEST(Playlist, EnumNames) {
  EXPECT_EQ(name(Motion::still), "still");
  EXPECT_EQ(name(Motion::turntable), "turntable");
  EXPECT_EQ(name(Motion::orbit), "orbit");
  EXPECT_EQ(name(Schedule::sequential), "sequential");
  EXPECT_EQ(name(Schedule::wallclock), "wallclock");
}

// The base library every layer shares: the fd owner, errno text, checked number parsing and the
// enum name tables.
#include "base/errno_text.h"
#include "base/names.h"
#include "base/parse.h"
#include "base/read_file.h"
#include "base/unique_fd.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

namespace {

bool is_open(int fd) {
  return fcntl(fd, F_GETFD) != -1;
}

TEST(BaseUniqueFd, ClosesWhenTheOwnerGoes) {
  int raw = -1;
  {
    base::UniqueFd fd(::open("/dev/null", O_RDONLY | O_CLOEXEC));
    ASSERT_TRUE(fd);
    raw = fd.get();
    EXPECT_TRUE(is_open(raw));
  }
  EXPECT_FALSE(is_open(raw));
}

TEST(BaseUniqueFd, MovesOwnershipAndResetsCloseTheOld) {
  base::UniqueFd a(::open("/dev/null", O_RDONLY | O_CLOEXEC));
  const int first = a.get();
  base::UniqueFd b(std::move(a));
  EXPECT_FALSE(a);  // NOLINT(bugprone-use-after-move): the moved-from owner holds nothing
  EXPECT_EQ(b.get(), first);
  base::UniqueFd c;
  EXPECT_FALSE(c);
  c = std::move(b);
  EXPECT_EQ(c.get(), first);
  base::UniqueFd& same = c;
  c = std::move(same);  // a self-move keeps the descriptor
  EXPECT_EQ(c.get(), first);
  EXPECT_TRUE(is_open(first));
  const int second = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  c.reset(second);
  EXPECT_FALSE(is_open(first));
  EXPECT_EQ(c.get(), second);
  const int released = c.release();
  EXPECT_FALSE(c);
  EXPECT_TRUE(is_open(released));
  ::close(released);
}

TEST(BaseErrnoText, SaysWhatTheCodeMeans) {
  EXPECT_EQ(base::errno_text(ENOENT), "No such file or directory");
  EXPECT_EQ(base::errno_text(EACCES), "Permission denied");
  EXPECT_FALSE(base::errno_text(123456).empty());
}

TEST(BaseParse, IntegersWholeTextInRange) {
  int value = 7;
  EXPECT_TRUE(base::parse_int("42", 0, 100, value));
  EXPECT_EQ(value, 42);
  EXPECT_TRUE(base::parse_int("-5", -10, 10, value));
  EXPECT_EQ(value, -5);
  EXPECT_TRUE(base::parse_int("100", 0, 100, value));
  EXPECT_EQ(value, 100);
  for (const char* text : {"", " 1", "1 ", "+1", "1x", "0x10", "1.0", "101", "-1", "99999999999", "abc"}) {
    int out = 7;
    EXPECT_FALSE(base::parse_int(text, 0, 100, out)) << "'" << text << "'";
    EXPECT_EQ(out, 7) << "a refused text leaves the value alone: '" << text << "'";
  }
  long long big = 0;
  EXPECT_TRUE(base::parse_int("3153600000000", 0, LLONG_MAX, big));
  EXPECT_EQ(big, 3153600000000LL);
  int byte = 0;
  EXPECT_TRUE(base::parse_int("ff", 0, 255, byte, 16));
  EXPECT_EQ(byte, 255);
  EXPECT_FALSE(base::parse_int("fg", 0, 255, byte, 16));
}

TEST(BaseParse, NumbersFiniteWholeText) {
  double value = 1.0;
  EXPECT_TRUE(base::parse_number("59.94", value));
  EXPECT_DOUBLE_EQ(value, 59.94);
  EXPECT_TRUE(base::parse_number("-2.5e-1", value));
  EXPECT_DOUBLE_EQ(value, -0.25);
  for (const char* text : {"", "inf", "nan", "1e", "1,5", " 1", "+1", "1.0Hz", "1e999"}) {
    double out = 1.0;
    EXPECT_FALSE(base::parse_number(text, out)) << "'" << text << "'";
    EXPECT_EQ(out, 1.0) << "'" << text << "'";
  }
  float single = 0.0f;
  EXPECT_TRUE(base::parse_number("0.5", single));
  EXPECT_EQ(single, 0.5f);
}

TEST(BaseParse, SizesAreTwoPositiveIntegersJoinedByX) {
  int w = 0, h = 0;
  EXPECT_TRUE(base::parse_size("1920x1080", 8192, w, h));
  EXPECT_EQ(w, 1920);
  EXPECT_EQ(h, 1080);
  for (const char* text :
       {"", "1920", "1920x", "x1080", "0x10", "10x0", "-1x5", "1920x1080x3", "1920 x1080", "8193x10", "10X10"}) {
    int a = 3, b = 4;
    EXPECT_FALSE(base::parse_size(text, 8192, a, b)) << "'" << text << "'";
    EXPECT_EQ(a, 3);
    EXPECT_EQ(b, 4);
  }
}

enum class Colour : std::uint8_t { red, green, blue };
constexpr base::Name<Colour> kColours[] = {{Colour::red, "red"}, {Colour::green, "green"}, {Colour::blue, "blue"}};
static_assert(base::in_enum_order(kColours));
constexpr base::Name<Colour> kSkipsGreen[] = {{Colour::red, "red"}, {Colour::blue, "blue"}};
static_assert(!base::in_enum_order(kSkipsGreen));

TEST(BaseNames, OneTableNamesParsesAndLists) {
  EXPECT_EQ(base::name_of(kColours, Colour::green), "green");
  EXPECT_EQ(base::name_of(kSkipsGreen, Colour::green), "?");
  Colour colour = Colour::red;
  EXPECT_TRUE(base::parse_name(kColours, "blue", colour));
  EXPECT_EQ(colour, Colour::blue);
  EXPECT_FALSE(base::parse_name(kColours, "Blue", colour));
  EXPECT_FALSE(base::parse_name(kColours, "", colour));
  EXPECT_EQ(colour, Colour::blue);
  EXPECT_EQ(base::names_of(kColours), (std::vector<std::string>{"red", "green", "blue"}));
  EXPECT_EQ(base::names_text(kColours), "red, green, blue");
  EXPECT_EQ(base::names_text(kColours, " or "), "red, green or blue");
  EXPECT_EQ(base::join_names({"one"}, " or "), "one");
  EXPECT_EQ(base::join_names({}, " or "), "");
}

// A folder of its own per test, removed after it.
class BaseReadFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("base-read-file-" + std::to_string(::getpid()) + "-" +
                                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(BaseReadFile, ReadsARegularFileWholeAndThroughALink) {
  const std::string text = std::string("first line\n") + std::string(100000, 'x') + '\0' + "after a zero byte";
  std::ofstream(path("playlist.toml"), std::ios::binary) << text;
  std::filesystem::create_symlink(path("playlist.toml"), path("link.toml"));
  for (const char* name : {"playlist.toml", "link.toml"}) {
    std::string out, error;
    ASSERT_TRUE(base::read_regular_file(path(name), "playlist", base::kMiB, out, error)) << error;
    EXPECT_EQ(out, text);
    EXPECT_EQ(error, "");
  }
  std::ofstream(path("empty.toml")).close();
  std::string out = "stale", error;
  ASSERT_TRUE(base::read_regular_file(path("empty.toml"), "playlist", base::kMiB, out, error)) << error;
  EXPECT_EQ(out, "");
}

// What would block (a FIFO with no writer) or never end (a device) is refused before any read,
// each saying what it is; the test would hang on the FIFO if the open or the read blocked.
TEST_F(BaseReadFile, RefusesEveryKindThatIsNotARegularFile) {
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
  std::filesystem::create_directories(path("folder"));
  base::UniqueFd listener(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string socket_path = path("socket");
  ASSERT_LT(socket_path.size(), sizeof address.sun_path);
  socket_path.copy(address.sun_path, socket_path.size());
  ASSERT_EQ(::bind(listener.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  std::filesystem::create_symlink(path("fifo"), path("link-to-fifo"));
  const std::pair<std::string, std::string> cases[] = {
      {path("fifo"), "a FIFO"},
      {path("link-to-fifo"), "a FIFO"},
      {path("folder"), "a folder"},
      {"/dev/zero", "a character device"},
      {"/dev/null", "a character device"},
  };
  for (const auto& [file, kind] : cases) {
    std::string out = "stale", error;
    EXPECT_FALSE(base::read_regular_file(file, "calibration", base::kMiB, out, error)) << file;
    EXPECT_EQ(error, file + ": the calibration is " + kind + ", not a regular file");
    EXPECT_EQ(out, "stale");  // nothing read, nothing changed
  }
  // A socket file cannot be opened at all; it is still refused, with the system's reason.
  std::string out, error;
  EXPECT_FALSE(base::read_regular_file(socket_path, "board file", base::kMiB, out, error));
  EXPECT_EQ(error.rfind(socket_path + ": cannot open the board file (", 0), 0u) << error;
}

TEST_F(BaseReadFile, RefusesAFileOverItsLimitBeforeReadingIt) {
  std::ofstream(path("big.json"), std::ios::binary) << std::string(3 * base::kKiB + 1, 'a');
  std::string out, error;
  EXPECT_FALSE(base::read_regular_file(path("big.json"), "calibration", 3 * base::kKiB, out, error));
  EXPECT_EQ(error, path("big.json") + ": the calibration is 3.0 KiB (3073 bytes); at most 3.0 KiB (3072 bytes) is read");
  EXPECT_TRUE(base::read_regular_file(path("big.json"), "calibration", 3 * base::kKiB + 1, out, error)) << error;
  EXPECT_EQ(out.size(), 3 * base::kKiB + 1);
  error.clear();
  EXPECT_FALSE(base::read_regular_file(path("missing.toml"), "display file", base::kMiB, out, error));
  EXPECT_EQ(error, path("missing.toml") + ": cannot open the display file (No such file or directory)");
}

TEST(BaseByteSize, SaysSizesAsPeopleReadThem) {
  EXPECT_EQ(base::byte_size_text(0), "0 bytes");
  EXPECT_EQ(base::byte_size_text(1023), "1023 bytes");
  EXPECT_EQ(base::byte_size_text(1024), "1.0 KiB");
  EXPECT_EQ(base::byte_size_text(64 * base::kMiB), "64.0 MiB");
  EXPECT_EQ(base::byte_size_text(3 * base::kGiB / 2), "1.5 GiB");
}

}  // namespace

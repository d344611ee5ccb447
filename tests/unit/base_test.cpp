// The base library every layer shares: the fd owner, errno text, checked number parsing and the
// enum name tables.
#include "base/errno_text.h"
#include "base/names.h"
#include "base/parse.h"
#include "base/unique_fd.h"

#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <climits>
#include <cstdint>
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

}  // namespace

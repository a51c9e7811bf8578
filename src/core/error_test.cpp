#include "core/error.hpp"

#include <gtest/gtest.h>

#include <new>
#include <string>
#include <vector>

namespace neomesh {
namespace {

std::string message_of(const std::exception& e) {
  return user_message(e);
}

// The message for what `act` throws while `activity` is in force.
template <typename Act>
std::string message_while(const char* activity, Act&& act) {
  try {
    const Activity doing(activity);
    act();
  } catch (const std::exception& e) {
    return user_message(e);
  }
  return "no exception";
}

TEST(Shorten, KeepsShortTextAndCutsLongTextSayingItsLength) {
  EXPECT_EQ(shorten("abc"), "abc");
  const std::string cut = shorten(std::string(30000, 'x'));
  EXPECT_LE(cut.size(), 60u);
  EXPECT_NE(cut.find("(30000 characters)"), std::string::npos) << cut;
}

TEST(UserMessage, KeepsAnErrorsOwnMessage) {
  EXPECT_EQ(message_of(Error("in.msh: cell 3 is inverted")), "in.msh: cell 3 is inverted");
}

TEST(UserMessage, SaysOutOfMemoryWithTheActivityInsteadOfBadAlloc) {
  const std::string message = message_while("reading big.msh", [] { throw std::bad_alloc(); });
  EXPECT_EQ(message.find("bad_alloc"), std::string::npos) << message;
  EXPECT_NE(message.find("out of memory while reading big.msh"), std::string::npos) << message;
}

TEST(UserMessage, SaysASizeIsTooLargeInsteadOfMaxSize) {
  const std::string message = message_while("reading huge.msh", [] {
    std::vector<double> v;
    v.resize(v.max_size() + 1);  // std::length_error "cannot create std::vector larger..."
  });
  EXPECT_EQ(message.find("max_size"), std::string::npos) << message;
  EXPECT_NE(message.find("a size is too large while reading huge.msh"), std::string::npos)
      << message;
}

TEST(UserMessage, SaysANumberCouldNotBeReadInsteadOfStoi) {
  const std::string message =
      message_while("reading sizes.txt", [] { (void)std::stoi("not a number"); });
  EXPECT_EQ(message.find("stoi"), std::string::npos) << message;
  EXPECT_NE(message.find("a number could not be read while reading sizes.txt"), std::string::npos)
      << message;
}

TEST(UserMessage, IsOneLineOfBoundedLength) {
  const std::string message = message_of(Error("first\nsecond " + std::string(5000, 'y')));
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_LE(message.size(), 1000u);
}

TEST(Activity, AnActivityLeftNormallyIsNotBlamed) {
  { const Activity done("reading a.msh"); }
  const std::string message = message_while("writing b.vtu", [] { throw std::bad_alloc(); });
  EXPECT_NE(message.find("while writing b.vtu"), std::string::npos) << message;
  EXPECT_EQ(message.find("a.msh"), std::string::npos) << message;
}

}  // namespace
}  // namespace neomesh

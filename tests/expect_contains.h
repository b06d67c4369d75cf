#pragma once
// EXPECT_CONTAINS(text, part): the test fails, printing the text, unless `part` occurs in it.
#include <gtest/gtest.h>

#include <string>

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "text: " << (haystack)

// gtest assertions on gs::Status and gs::Result: ASSERT_TRUE(Succeeded(call)) prints the core's
// message when the call fails.
#pragma once

#include "Status.h"

#include <gtest/gtest.h>

#include <string>

namespace gs_test
{

inline ::testing::AssertionResult Succeeded(const gs::Status& status)
{
  if (status.Ok())
  {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << status.Message();
}

// EXPECT_TRUE(FailedWith(call, "words")): the call failed with an error (not an abort) whose
// message holds `words`.
inline ::testing::AssertionResult FailedWith(const gs::Status& status, const std::string& words)
{
  if (status.Ok() || status.IsAborted())
  {
    return ::testing::AssertionFailure() << (status.Ok() ? "succeeded" : "aborted")
                                         << ", expected an error saying \"" << words << "\"";
  }
  if (status.Message().find(words) == std::string::npos)
  {
    return ::testing::AssertionFailure()
      << "the error \"" << status.Message() << "\" does not say \"" << words << "\"";
  }
  return ::testing::AssertionSuccess();
}

} // namespace gs_test

// gtest assertions on gs::Status and gs::Result: ASSERT_TRUE(Succeeded(call)) prints the core's
// message when the call fails.
#pragma once

#include "Status.h"

#include <gtest/gtest.h>

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

} // namespace gs_test

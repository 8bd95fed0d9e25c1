// The message of the lvdif::Error a call throws, its code checked: the one
// helper of the tests that check what a refusal says (each test wrote its own
// try/catch: 39 of them in Core's tests).
#pragma once

#include "lvdif/Error.h"

#include <gtest/gtest.h>

#include <string>

namespace errortest
{

/// The message of the lvdif::Error that call() throws. The test fails when it
/// throws none ("no error" is returned, so the caller's check of the message
/// fails at its own line too) or one of another code (its message is still
/// returned). Other exceptions pass through to GoogleTest.
template <typename Call>
std::string errorMessageOf(Call&& call, lvdif::ErrorCode expected)
{
  try
  {
    call();
  }
  catch (const lvdif::Error& e)
  {
    EXPECT_STREQ(lvdif::toString(e.code()), lvdif::toString(expected)) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no lvdif::Error thrown (expected " << lvdif::toString(expected) << ")";
  return "no error";
}

} // namespace errortest

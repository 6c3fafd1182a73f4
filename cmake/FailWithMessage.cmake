# cmake -DMESSAGE=... -P FailWithMessage.cmake: a test that fails, saying why.
message(FATAL_ERROR "${MESSAGE}")

// The messages between MPI ranks (harness/run/rank_messages.hpp): every field survives the
// round trip byte for byte (empty fields, NULs, newlines), the busy time exactly, and a
// truncated or padded message is refused rather than misread.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "harness/run/rank_messages.hpp"

using namespace dabench;

TEST_CASE("rank messages: fields round trip byte for byte", "[run][mpi]") {
  const std::vector<std::string> fields = {"", std::string("a\0b", 3), "1,2,3\n4,5,6\n", std::string(70000, 'x')};
  const std::string packed = pack_fields(fields);
  CHECK(packed.size() == 8 + 4 * 8 + 0 + 3 + 12 + 70000);
  CHECK(unpack_fields(packed) == fields);
  CHECK(unpack_fields(pack_fields({})).empty());
}

TEST_CASE("rank messages: hello, start, block result and block decode to what was sent", "[run][mpi]") {
  const Hello hello = decode_hello(encode(Hello{"node7", "f00d", 12, "e.ini: no such file"}));
  CHECK(hello.host == "node7");
  CHECK(hello.fingerprint == "f00d");
  CHECK(hello.threads == 12);
  CHECK(hello.error == "e.ini: no such file");

  const Start start = decode_start(encode(Start{"", 41, 3}));
  CHECK(start.error.empty());
  CHECK(start.first_block == 41);
  CHECK(start.skip_in_first == 3);
  CHECK(decode_start(encode(Start{"out: already holds a run"})).error == "out: already holds a run");

  BlockResult sent;
  sent.block = 123456789012LL;
  sent.interrupted = true;
  sent.busy_seconds = 0.1 + 0.2;  // not a short decimal: must come back exactly
  sent.texts = {"row 1\nrow 2\n", "", "last\n"};
  const BlockResult received = decode_block_result(encode(sent));
  CHECK(received.block == sent.block);
  CHECK(received.interrupted);
  CHECK(received.busy_seconds == sent.busy_seconds);
  CHECK(received.texts == sent.texts);
  const BlockResult request = decode_block_result(encode(BlockResult{}));
  CHECK(request.block == kNoBlock);
  CHECK_FALSE(request.interrupted);
  CHECK(request.texts.empty());

  CHECK(decode_block(encode_block(77)) == 77);
  CHECK(decode_block(encode_block(kNoBlock)) == kNoBlock);
}

TEST_CASE("rank messages: truncated, padded or mistyped messages are refused", "[run][mpi]") {
  const std::string packed = pack_fields({"abc", "de"});
  CHECK_THROWS_AS(unpack_fields(packed.substr(0, packed.size() - 1)), std::runtime_error);
  CHECK_THROWS_AS(unpack_fields(packed + "z"), std::runtime_error);
  CHECK_THROWS_AS(unpack_fields(packed.substr(0, 5)), std::runtime_error);
  CHECK_THROWS_AS(decode_block(pack_fields({"12x"})), std::runtime_error);
  CHECK_THROWS_AS(decode_block(pack_fields({""})), std::runtime_error);
  CHECK_THROWS_AS(decode_hello(pack_fields({"host", "fingerprint"})), std::runtime_error);
}

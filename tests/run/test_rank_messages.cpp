// The messages between MPI ranks (harness/run/rank_messages.hpp): every field survives the
// round trip byte for byte (empty fields, NULs, newlines), the busy and unit times exactly, and a
// truncated or padded message is refused rather than misread.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "harness/run/rank_messages.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

TEST_CASE("rank messages: fields round trip byte for byte", "[run][mpi]") {
  const std::vector<std::string> fields = {"", std::string("a\0b", 3), "1,2,3\n4,5,6\n", std::string(70000, 'x')};
  const std::string packed = pack_fields(fields);
  CHECK(packed.size() == 8 + 4 * 8 + 0 + 3 + 12 + 70000);
  CHECK(unpack_fields(packed) == fields);
  CHECK(unpack_fields(pack_fields({})).empty());
}

TEST_CASE("rank messages: hello, start, chunk result and chunk decode to what was sent", "[run][mpi]") {
  const Hello hello = decode_hello(encode(Hello{"node7", "f00d", 12, "e.ini: no such file"}));
  CHECK(hello.host == "node7");
  CHECK(hello.fingerprint == "f00d");
  CHECK(hello.threads == 12);
  CHECK(hello.error == "e.ini: no such file");

  CHECK(decode_start(encode(Start{""})).error.empty());
  CHECK(decode_start(encode(Start{"out: already holds a run"})).error == "out: already holds a run");

  ChunkResult sent;
  sent.chunk = WorkChunk{123456789012LL, 123456789015LL};
  sent.interrupted = true;
  sent.busy_seconds = 0.1 + 0.2;  // not a short decimal: must come back exactly
  sent.unit_seconds = {1.0 / 3.0, 0.0, 1e-300};
  sent.texts = {"row 1\nrow 2\n", "", "last\n"};
  const ChunkResult received = decode_chunk_result(encode(sent));
  REQUIRE(received.chunk);
  CHECK(received.chunk->begin == sent.chunk->begin);
  CHECK(received.chunk->end == sent.chunk->end);
  CHECK(received.interrupted);
  CHECK(received.busy_seconds == sent.busy_seconds);
  CHECK(received.unit_seconds == sent.unit_seconds);
  CHECK(received.texts == sent.texts);
  const ChunkResult request = decode_chunk_result(encode(ChunkResult{}));
  CHECK_FALSE(request.chunk);
  CHECK_FALSE(request.interrupted);
  CHECK(request.unit_seconds.empty());
  CHECK(request.texts.empty());

  const auto chunk = decode_chunk(encode_chunk(WorkChunk{77, 80}));
  REQUIRE(chunk);
  CHECK((chunk->begin == 77 && chunk->end == 80));
  CHECK_FALSE(decode_chunk(encode_chunk(std::nullopt)));
}

TEST_CASE("rank messages: truncated, padded or mistyped messages are refused", "[run][mpi]") {
  const std::string packed = pack_fields({"abc", "de"});
  CHECK_THROWS_AS(unpack_fields(packed.substr(0, packed.size() - 1)), std::runtime_error);
  CHECK_THROWS_AS(unpack_fields(packed + "z"), std::runtime_error);
  CHECK_THROWS_AS(unpack_fields(packed.substr(0, 5)), std::runtime_error);
  CHECK_THROWS_AS(decode_chunk(pack_fields({"12x", "13"})), std::runtime_error);
  CHECK_THROWS_AS(decode_chunk(pack_fields({"", "1"})), std::runtime_error);
  CHECK_THROWS_AS(decode_chunk(pack_fields({"5", "5"})), std::runtime_error);  // an empty chunk
  CHECK_THROWS_AS(decode_chunk(pack_fields({"7"})), std::runtime_error);
  ChunkResult short_times;
  short_times.chunk = WorkChunk{0, 2};
  short_times.unit_seconds = {1.0};  // one time for two units
  CHECK_THROWS_AS(decode_chunk_result(encode(short_times)), std::runtime_error);
  CHECK_THROWS_AS(decode_hello(pack_fields({"host", "fingerprint"})), std::runtime_error);
}

}  // namespace DABENCH_TEST_FILE

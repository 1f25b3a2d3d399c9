// forge_commands URL CHANNEL KEY_NAME RATE SECONDS: publishes wind commands on CHANNEL that claim
// the key KEY_NAME but carry random MACs, RATE a second for SECONDS, each from its own client id
// and sequence, dated now; prints how many it sent. For tests that a server with keys refuses a
// flood of forgeries, counts them and keeps its pace.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>

#include "flagsim/wind_command_t.hpp"
#include "messages/bus.hpp"
#include "messages/utime.hpp"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: forge_commands URL CHANNEL KEY_NAME RATE SECONDS\n");
    return 2;
  }
  flagsim::Bus bus(argv[1]);
  const std::string channel = argv[2];
  const double rate = std::atof(argv[4]), seconds = std::atof(argv[5]);
  std::mt19937 random(2024);
  flagsim::wind_command_t forged{};
  forged.key_id = argv[3];
  forged.velocity[0] = 30;  // a gale, if it were ever taken
  const auto start = std::chrono::steady_clock::now();
  const long total = static_cast<long>(rate * seconds);
  for (long sent = 0; sent < total; ++sent) {
    // Paced: the sent-th command goes out at sent / rate seconds.
    std::this_thread::sleep_until(start + std::chrono::duration<double>(double(sent) / rate));
    forged.client_id = "forger-" + std::to_string(sent % 97);
    forged.sequence = sent;
    forged.utime = flagsim::UnixMicros();
    for (uint8_t& byte : forged.mac) byte = static_cast<uint8_t>(random());
    bus.Publish(channel, forged);
  }
  std::printf("%ld\n", total);
  return 0;
}

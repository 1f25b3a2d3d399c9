// lcm_spray URL COUNT CHANNEL...: publishes COUNT hostile messages on each channel (empty,
// truncated, oversized, random, lying lengths), for tests that a server survives them.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "messages/bus.hpp"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: lcm_spray URL COUNT CHANNEL...\n");
    return 2;
  }
  flagsim::Bus bus(argv[1]);
  const int count = std::atoi(argv[2]);
  std::mt19937 random(12345);
  for (int i = 0; i < count; ++i) {
    for (int c = 3; c < argc; ++c) {
      std::vector<uint8_t> bytes;
      switch (i % 4) {
        case 0:
          bytes.resize(random() % 8);
          break;  // shorter than a fingerprint
        case 1:
          bytes.assign(60000, 0xff);
          break;  // large, all lengths -1
        case 2:
          bytes.resize(8 + random() % 300);
          break;  // random after a random fingerprint
        case 3:
          bytes.assign(32, 0x7f);
          break;  // huge positive lengths
      }
      if (i % 4 == 2) {
        for (uint8_t& b : bytes) b = static_cast<uint8_t>(random());
      }
      bus.Publish(argv[c], bytes.data(), bytes.size());
      // Paced: LCM over UDP loses unpaced bursts, and the test counts what arrives.
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  }
  std::printf("sprayed %d messages on each of %d channels\n", count, argc - 3);
  return 0;
}

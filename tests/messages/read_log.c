/* Reads an LCM event log with lcm-gen's C types and liblcm's log reader, and prints a line for
 * each STATE, PARAMS, STATUS, TIMELINE, FRAME, TILE and CHECKPOINT message: the reference whose
 * lines the Lua reader (read_log.lua) must print the same. 64-bit hashes and ids are printed as
 * 16 hex digits, as flagctl and the gateway print them.
 * Usage: read_log LOG PREFIX; exit 1 if a message of those channels does not decode. */
#include <inttypes.h>
#include <lcm/eventlog.h>
#include <stdio.h>
#include <string.h>

#include "flagsim_checkpoint_t.h"
#include "flagsim_frame_t.h"
#include "flagsim_params_t.h"
#include "flagsim_state_t.h"
#include "flagsim_status_t.h"
#include "flagsim_tile_t.h"
#include "flagsim_timeline_t.h"

static int failures = 0;

static const char* Unprefixed(const char* channel, const char* prefix) {
  const size_t length = strlen(prefix);
  return strncmp(channel, prefix, length) == 0 ? channel + length : NULL;
}

static uint64_t Bits(int64_t value) { return (uint64_t)value; }

static void Undecodable(const char* name, int64_t event) {
  printf("%s event %" PRId64 ": does not decode\n", name, event);
  ++failures;
}

static void PrintEvent(const lcm_eventlog_event_t* event, const char* name) {
  const void* data = event->data;
  const int size = event->datalen;
  if (strcmp(name, "STATE") == 0) {
    flagsim_state_t m;
    if (flagsim_state_t_decode(data, 0, size, &m) != size) {
      Undecodable(name, event->eventnum);
      return;
    }
    printf("STATE step=%" PRId64 " state_hash=%016" PRIx64 " server_id=%016" PRIx64
           " num_values=%d position0=%.9g\n",
           m.step, Bits(m.state_hash), Bits(m.server_id), m.num_values,
           m.num_values > 0 ? m.position[0] : 0.0f);
    flagsim_state_t_decode_cleanup(&m);
  } else if (strcmp(name, "PARAMS") == 0) {
    flagsim_params_t m;
    if (flagsim_params_t_decode(data, 0, size, &m) != size) {
      Undecodable(name, event->eventnum);
      return;
    }
    printf("PARAMS num_parameters=%d", m.num_parameters);
    for (int i = 0; i < m.num_parameters; ++i) {
      printf(" %s=%s", m.parameters[i].name, m.parameters[i].value_text);
    }
    printf("\n");
    flagsim_params_t_decode_cleanup(&m);
  } else if (strcmp(name, "STATUS") == 0) {
    flagsim_status_t m;
    if (flagsim_status_t_decode(data, 0, size, &m) != size) {
      Undecodable(name, event->eventnum);
      return;
    }
    printf("STATUS step=%" PRId64 " integrator=%s threads=%d server_id=%016" PRIx64 "\n", m.step,
           m.integrator, m.threads, Bits(m.server_id));
    flagsim_status_t_decode_cleanup(&m);
  } else if (strcmp(name, "TIMELINE") == 0) {
    flagsim_timeline_t m;
    if (flagsim_timeline_t_decode(data, 0, size, &m) != size) {
      Undecodable(name, event->eventnum);
      return;
    }
    printf("TIMELINE step=%" PRId64 " last_key_time=%.17g num_keys=%d\n", m.step, m.last_key_time,
           m.num_keys);
    flagsim_timeline_t_decode_cleanup(&m);
  } else if (strcmp(name, "FRAME") == 0) {
    flagsim_frame_t m;
    if (flagsim_frame_t_decode(data, 0, size, &m) != size) {
      Undecodable(name, event->eventnum);
      return;
    }
    printf("FRAME frame_id=%" PRId64 " frame_hash=%016" PRIx64 " num_tiles=%d\n", m.frame_id,
           Bits(m.frame_hash), m.num_tiles);
    flagsim_frame_t_decode_cleanup(&m);
  } else if (strcmp(name, "TILE") == 0) {
    flagsim_tile_t m;
    if (flagsim_tile_t_decode(data, 0, size, &m) != size) {
      Undecodable(name, event->eventnum);
      return;
    }
    printf("TILE frame_id=%" PRId64 " tile_index=%d pixel_hash=%016" PRIx64 " num_bytes=%d\n", m.frame_id,
           m.tile_index, Bits(m.pixel_hash), m.num_bytes);
    flagsim_tile_t_decode_cleanup(&m);
  } else if (strcmp(name, "CHECKPOINT") == 0) {
    flagsim_checkpoint_t m;
    if (flagsim_checkpoint_t_decode(data, 0, size, &m) != size) {
      Undecodable(name, event->eventnum);
      return;
    }
    printf("CHECKPOINT step=%" PRId64 " reason=%s state_hash=%016" PRIx64
           " scene=%s last_key_time=%.17g num_nodes=%d\n",
           m.step, m.reason, Bits(m.state_hash), m.scene.name, m.scene.timeline.last_key_time, m.num_nodes);
    flagsim_checkpoint_t_decode_cleanup(&m);
  }
}

int main(int argc, char** argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: read_log LOG PREFIX\n");
    return 2;
  }
  lcm_eventlog_t* log = lcm_eventlog_create(argv[1], "r");
  if (log == NULL) {
    fprintf(stderr, "read_log: cannot open %s\n", argv[1]);
    return 2;
  }
  lcm_eventlog_event_t* event;
  while ((event = lcm_eventlog_read_next_event(log)) != NULL) {
    const char* name = Unprefixed(event->channel, argv[2]);
    if (name != NULL) PrintEvent(event, name);
    lcm_eventlog_free_event(event);
  }
  lcm_eventlog_destroy(log);
  return failures == 0 ? 0 : 1;
}

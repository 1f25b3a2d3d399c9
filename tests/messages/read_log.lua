-- Reads an LCM event log with lcm-gen's Lua types and Debian's liblcm-lua (Lua 5.2), and prints
-- a line for each STATE, PARAMS, STATUS, TIMELINE, FRAME, TILE and CHECKPOINT message, the same
-- lines as read_log.c prints with the C types.
--
-- liblcm-lua has no log reader, so the events are read here. An event is: the sync word
-- 0xEDA1DA01, int64 event number, int64 timestamp (us), int32 channel length, int32 data length,
-- the channel, the data; every number big-endian.
--
-- Lua 5.2 numbers are doubles, and the types decode an int64 into one: a hash or server id (any
-- 64-bit value) loses its low bits. They are printed from the message's own 8 bytes instead, read
-- at the field's offset, as messages/README.md says a Lua client should compare them.
-- Usage: lua5.2 read_log.lua TYPES_DIR LOG PREFIX; exit 1 if a message does not decode.

-- Errors are printed on stdout: stderr carries liblcm-lua's warnings of lost precision.

local types_dir, log_path, prefix = arg[1], arg[2], arg[3]
package.path = types_dir .. "/?.lua;" .. types_dir .. "/?/init.lua;" .. package.path
local flagsim

local kSyncWord = 0xEDA1DA01
local kFingerprintBytes = 8  -- every message starts with its type's fingerprint

-- The unsigned big-endian integer in bytes [at, at + count) of text (count <= 4: exact).
local function Unsigned(text, at, count)
  local value = 0
  for i = at, at + count - 1 do value = value * 256 + text:byte(i) end
  return value
end

-- The int64 at byte offset `offset` of a message, as 16 hex digits (two's complement).
local function Int64Hex(data, offset)
  return string.format("%08x%08x", Unsigned(data, offset + 1, 4), Unsigned(data, offset + 5, 4))
end

-- Offset of an int64 field after the fixed fields and strings before it: `fixed` bytes of
-- fixed-size fields in all (fingerprint included), and the strings, each encoded as an int32
-- length, its bytes and a terminating 0.
local function OffsetAfter(fixed, strings)
  local offset = fixed
  for _, text in ipairs(strings) do offset = offset + 4 + #text + 1 end
  return offset
end

local function Joined(parameters)
  local parts = {}
  for i, row in ipairs(parameters) do parts[i] = string.format(" %s=%s", row.name, row.value_text) end
  return table.concat(parts)
end

-- Offsets of the 64-bit hashes and ids, from the .lcm files' field order (sizes in bytes).
local kStateHashOffset = kFingerprintBytes + 3 * 8                 -- state_t: utime, step, sim_time
local kStateServerIdOffset = kFingerprintBytes + 4 * 8 + 2 * 4 + 2 * 4 + 3 * 8 + 8 + 3 * 8 + 2 * 8
                                                                   --   ... wind_gust, kinetic_energy
local kCheckpointHashOffset = kFingerprintBytes + 3 * 8            -- checkpoint_t likewise
local kFrameHashOffset = kFingerprintBytes + 4 * 8 + 3 * 4 + 1 + 8  -- frame_t: utime .. request_id
local kPixelHashOffset = kFingerprintBytes + 8 + 8 + 4 + 4 * 2 + 1  -- tile_t: utime .. encoding
local kStatusFixedBeforeIntegrator = kFingerprintBytes + 6 * 8 + 3 * 4  -- status_t: utime .. threads
local kStatusFixedBetweenStrings = 1 + 1 + 4 + 8 + 8 * 8 + 8 + 8 + 3 * 8 + 5 * 8 + 8
                        -- sleeping, paused, steps_owed, time_scale .. messages_dropped, commands_unsigned .. recoveries

local printers = {
  STATE = function(data)
    local m = flagsim.state_t.decode(data)
    return string.format("STATE step=%d state_hash=%s server_id=%s num_values=%d position0=%.9g", m.step,
                         Int64Hex(data, kStateHashOffset), Int64Hex(data, kStateServerIdOffset), m.num_values,
                         m.num_values > 0 and m.position[1] or 0)
  end,
  PARAMS = function(data)
    local m = flagsim.params_t.decode(data)
    return string.format("PARAMS num_parameters=%d%s", m.num_parameters, Joined(m.parameters))
  end,
  STATUS = function(data)
    local m = flagsim.status_t.decode(data)
    local server_id = OffsetAfter(kStatusFixedBeforeIntegrator + kStatusFixedBetweenStrings,
                                  {m.integrator, m.command_authentication, m.last_recovery})
    return string.format("STATUS step=%d integrator=%s threads=%d server_id=%s", m.step, m.integrator,
                         m.threads, Int64Hex(data, server_id))
  end,
  TIMELINE = function(data)
    local m = flagsim.timeline_t.decode(data)
    return string.format("TIMELINE step=%d last_key_time=%.17g num_keys=%d", m.step, m.last_key_time,
                         m.num_keys)
  end,
  FRAME = function(data)
    local m = flagsim.frame_t.decode(data)
    return string.format("FRAME frame_id=%d frame_hash=%s num_tiles=%d", m.frame_id,
                         Int64Hex(data, kFrameHashOffset), m.num_tiles)
  end,
  TILE = function(data)
    local m = flagsim.tile_t.decode(data)
    return string.format("TILE frame_id=%d tile_index=%d pixel_hash=%s num_bytes=%d", m.frame_id,
                         m.tile_index, Int64Hex(data, kPixelHashOffset), m.num_bytes)
  end,
  CHECKPOINT = function(data)
    local m = flagsim.checkpoint_t.decode(data)
    return string.format("CHECKPOINT step=%d reason=%s state_hash=%s scene=%s last_key_time=%.17g"
                         .. " num_nodes=%d", m.step, m.reason, Int64Hex(data, kCheckpointHashOffset),
                         m.scene.name, m.scene.timeline.last_key_time, m.num_nodes)
  end,
}

-- Every event of the log, each message of a printer's channel decoded and printed. Returns the
-- count of messages that did not decode.
local function ReadLog()
  flagsim = require("flagsim")
  local file = assert(io.open(log_path, "rb"))
  local log = file:read("*a")
  file:close()

  local at, failures = 1, 0
  while at <= #log do
    if at + 27 > #log then error(string.format("a cut event header at byte %d", at - 1)) end
    if Unsigned(log, at, 4) ~= kSyncWord then error(string.format("no sync word at byte %d", at - 1)) end
    local event_number = Unsigned(log, at + 4, 4) * 2 ^ 32 + Unsigned(log, at + 8, 4)
    local channel_length, data_length = Unsigned(log, at + 20, 4), Unsigned(log, at + 24, 4)
    local channel_at = at + 28
    local data_at = channel_at + channel_length
    if data_at + data_length - 1 > #log then error(string.format("event %d is cut", event_number)) end
    local channel = log:sub(channel_at, data_at - 1)
    local data = log:sub(data_at, data_at + data_length - 1)
    at = data_at + data_length

    if channel:sub(1, #prefix) == prefix then
      local name = channel:sub(#prefix + 1)
      local printer = printers[name]
      if printer then
        local ok, line = pcall(printer, data)
        if ok then
          print(line)
        else
          print(string.format("%s event %d: does not decode: %s", name, event_number, line))
          failures = failures + 1
        end
      end
    end
  end
  return failures
end

local ok, failures = xpcall(ReadLog, debug.traceback)
if not ok then print(failures) end
os.exit(ok and failures == 0 and 0 or 1)

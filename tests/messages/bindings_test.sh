#!/usr/bin/env bash
# Every binding lcm-gen writes reads our messages: no type, field or constant name in
# messages/*.lcm is a keyword of C, C++, Java, Python, Lua or C#; lcm-gen writes all six from
# them; and each compiles or loads where its toolchain is installed. C (against liblcm) and Lua
# (Debian's liblcm-lua) go further and decode a live server's log (STATE, PARAMS, STATUS,
# TIMELINE, FRAME, TILE; CHECKPOINT from its inputs log), and the Lua lines must equal the C
# ones, 64-bit hashes included. A language whose toolchain is missing is skipped with a note.
# Usage: bindings_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1
build=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

source "$source_dir/tests/integration/checks.sh"
skip() { echo "skip  $1"; }
here=$source_dir/tests/messages
lcm_files=("$source_dir"/messages/*.lcm)
types=()
for file in "${lcm_files[@]}"; do
  name=${file##*/}
  types+=("${name%.lcm}")
done

# The type, field and constant names of one .lcm file, one a line.
names_in() {
  awk '{ sub(/\/\/.*/, ""); text = text " " $0 }
    END {
      n = split(text, parts, /[;{}]/)
      for (i = 1; i <= n; i++) {
        part = parts[i]
        gsub(/\[[^]]*\]/, "", part)
        gsub(/^[ \t]+|[ \t]+$/, "", part)
        if (part == "" || part ~ /^package[ \t]/) continue
        if (part ~ /^const[ \t]/) {
          sub(/^const[ \t]+[A-Za-z0-9_]+[ \t]+/, "", part)
          m = split(part, constants, ",")
          for (j = 1; j <= m; j++) {
            name = constants[j]
            sub(/=.*/, "", name)
            gsub(/[ \t]/, "", name)
            print name
          }
          continue
        }
        m = split(part, words, /[ \t]+/)
        print words[m]
      }
    }' "$1"
}

declare -A keywords=(
  [C]="auto break case char const continue default do double else enum extern float for goto if inline int
       long register restrict return short signed sizeof static struct switch typedef union unsigned void
       volatile while _Alignas _Alignof _Atomic _Bool _Complex _Generic _Imaginary _Noreturn _Static_assert
       _Thread_local"
  [C++]="alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t
         char32_t class compl concept const consteval constexpr constinit const_cast continue co_await
         co_return co_yield decltype default delete do double dynamic_cast else enum explicit export extern
         false float for friend goto if inline int long mutable namespace new noexcept not not_eq nullptr
         operator or or_eq private protected public register reinterpret_cast requires return short signed
         sizeof static static_assert static_cast struct switch template this thread_local throw true try
         typedef typeid typename union unsigned using virtual void volatile wchar_t while xor xor_eq"
  [Java]="abstract assert boolean break byte case catch char class const continue default do double else enum
          extends false final finally float for goto if implements import instanceof int interface long native
          new null package private protected public return short static strictfp super switch synchronized
          this throw throws transient true try void volatile while"
  [Python]="False None True and as assert async await break class continue def del elif else except finally
            for from global if import in is lambda nonlocal not or pass raise return try while with yield"
  [Lua]="and break do else elseif end false for function goto if in local nil not or repeat return then true
         until while"
  [C#]="abstract as base bool break byte case catch char checked class const continue decimal default
        delegate do double else enum event explicit extern false finally fixed float for foreach goto if
        implicit in int interface internal is lock long namespace new null object operator out override
        params private protected public readonly ref return sbyte sealed short sizeof stackalloc static
        string struct switch this throw true try typeof uint ulong unchecked unsafe ushort using virtual void
        volatile while"
)

echo "-- names against every target language's keywords"
checked=0
collisions=0
for file in "${lcm_files[@]}"; do
  while read -r name; do
    checked=$((checked + 1))
    for language in "${!keywords[@]}"; do
      for keyword in ${keywords[$language]}; do
        if [[ $name == "$keyword" ]]; then
          fail "${file##*/}: '$name' is a $language keyword"
          collisions=$((collisions + 1))
        fi
      done
    done
  done < <(names_in "$file")
done
if ((checked < 10 * ${#lcm_files[@]})); then fail "only $checked names read from ${#lcm_files[@]} files"
elif ((collisions == 0)); then pass "$checked names of ${#lcm_files[@]} types, none a keyword"; fi

echo "-- lcm-gen $(lcm-gen --version | awk '{print $2}')"
# generated DIR PATTERN: every type has its file, PATTERN with TYPE for the type's name.
generated() {
  local dir=$1 pattern=$2 missing=()
  for type in "${types[@]}"; do
    [[ -f $dir/${pattern//TYPE/$type} ]] || missing+=("${pattern//TYPE/$type}")
  done
  if ((${#missing[@]} == 0)); then pass "  ${#types[@]} files in ${dir#"$work"/}"
  else fail "  missing in ${dir#"$work"/}: ${missing[*]}"; fi
}
mkdir -p "$work/c"
expect 0 "C" lcm-gen --c --c-cpath "$work/c" --c-hpath "$work/c" "${lcm_files[@]}"
generated "$work/c" flagsim_TYPE.c
expect 0 "C++ (C++98)" lcm-gen --cpp --cpp-hpath "$work/cpp98" "${lcm_files[@]}"
generated "$work/cpp98" flagsim/TYPE.hpp
expect 0 "C++ (C++11)" lcm-gen --cpp --cpp-std=c++11 --cpp-hpath "$work/cpp11" "${lcm_files[@]}"
generated "$work/cpp11" flagsim/TYPE.hpp
expect 0 "Java" lcm-gen --java --jpath "$work/java" "${lcm_files[@]}"
generated "$work/java" flagsim/TYPE.java
expect 0 "Python" lcm-gen --python --ppath "$work/python" "${lcm_files[@]}"
generated "$work/python" flagsim/TYPE.py
expect 0 "Lua" lcm-gen --lua --lpath "$work/lua" "${lcm_files[@]}"
generated "$work/lua" flagsim/TYPE.lua
expect 0 "C#" lcm-gen --csharp --csharp-path "$work/csharp" "${lcm_files[@]}"
generated "$work/csharp" flagsim/TYPE.cs

echo "-- compiled or loaded"
# Warnings in generated code are lcm-gen's (-w); errors fail.
reader=""
if command -v gcc >/dev/null; then
  expect 0 "C: the types and a log reader compile and link against liblcm" \
    bash -c 'cd "$1" && gcc -std=c99 -O1 -w -c ./*.c &&
             gcc -std=c99 -O1 -Wall -Wextra -Werror -I. -o "$2" "$3" ./*.o -llcm' \
    _ "$work/c" "$work/read_log" "$here/read_log.c"
  [[ -x $work/read_log ]] && reader=$work/read_log
else skip "C: no gcc"; fi
if command -v g++ >/dev/null; then
  for type in "${types[@]}"; do echo "#include \"flagsim/$type.hpp\""; done >"$work/all_types.cpp"
  expect 0 "C++: C++98 output as C++98" g++ -std=c++98 -fsyntax-only -I"$work/cpp98" "$work/all_types.cpp"
  expect 0 "C++: C++98 output as C++17" g++ -std=c++17 -fsyntax-only -I"$work/cpp98" "$work/all_types.cpp"
  expect 0 "C++: C++11 output as C++17" g++ -std=c++17 -fsyntax-only -I"$work/cpp11" "$work/all_types.cpp"
else skip "C++: no g++"; fi
lcm_jar=/usr/share/java/lcm.jar
if command -v javac >/dev/null && [[ -f $lcm_jar ]]; then
  expect 0 "Java: javac against lcm.jar" javac -nowarn -cp "$lcm_jar" -d "$work/java/classes" \
    "$work"/java/flagsim/*.java
  classes=$(find "$work/java/classes" -name '*.class' 2>/dev/null | wc -l)
  if ((classes >= ${#types[@]})); then pass "  $classes classes"; else fail "  $classes classes"; fi
else skip "Java: no javac or no $lcm_jar (scripts/install-deps.sh --java)"; fi
if command -v python3 >/dev/null; then
  expect 0 "Python: byte-compiled" python3 -m py_compile "$work"/python/flagsim/*.py
else skip "Python: no python3"; fi
lua=""
if command -v lua5.2 >/dev/null && lua5.2 -e 'require("lcm")' 2>/dev/null; then
  lua=lua5.2
  expect 0 "Lua: every type loads with liblcm-lua" \
    lua5.2 -e "package.path = '$work/lua/?.lua;$work/lua/?/init.lua;' .. package.path
               local flagsim = require('flagsim')
               for _, type in ipairs({$(printf "'%s', " "${types[@]}")}) do
                 assert(flagsim[type] and flagsim[type].decode, type)
               end"
else skip "Lua: no lua5.2 with liblcm-lua (scripts/install-deps.sh installs them)"; fi
if command -v mcs >/dev/null || command -v csc >/dev/null; then
  skip "C#: Debian packages no LCM .NET library to compile against; only generated"
else skip "C#: no C# compiler (mcs or csc); only generated"; fi

if [[ -n $reader || -n $lua ]]; then
  echo "-- a live server's log, decoded"
  # flagd writes what it publishes straight into an LCM log (liblcm's file provider): no network.
  live=$work/live.lcmlog
  expect 0 "flagd for 2.5 s, its bus an LCM log" "$build/server/flagd" --lcm-url "file://$live?mode=w" \
    --duration 2.5 --set cols=12 --set rows=8 --record-inputs "$work/inputs.lcmlog" --log-level warn
  for log in live inputs; do
    if [[ -n $reader ]]; then
      expect 0 "C reads the $log log" "$reader" "$work/$log.lcmlog" FLAGSIM_
      cp "$work/out" "$work/$log.c.txt"
    fi
    if [[ -n $lua ]]; then
      expect 0 "Lua reads the $log log" bash -c '"$@" 2>"$0"' "$work/$log.lua.stderr" \
        lua5.2 "$here/read_log.lua" "$work/lua" "$work/$log.lcmlog" FLAGSIM_
      cp "$work/out" "$work/$log.lua.txt"
    fi
  done
  # count NAME FILE: the lines of NAME's messages.
  count() { grep -c "^$1 " "$2" || true; }
  for language in c lua; do
    [[ $language == c && -z $reader || $language == lua && -z $lua ]] && continue
    for name in STATE PARAMS STATUS TIMELINE FRAME TILE CHECKPOINT; do
      lines=$work/live.$language.txt
      [[ $name == CHECKPOINT ]] && lines=$work/inputs.$language.txt
      got=$(count $name "$lines")
      if ((got > 0)); then pass "  $language: $got $name"; else fail "  $language: no $name" "$lines"; fi
    done
  done
  if [[ -n $reader && -n $lua ]]; then
    for log in live inputs; do
      if diff "$work/$log.c.txt" "$work/$log.lua.txt" >"$work/diff"; then
        pass "Lua and C print the same $(wc -l <"$work/$log.c.txt") lines of the $log log"
      else fail "Lua and C differ on the $log log:" "$work/diff"; fi
    done
  fi
fi
finish

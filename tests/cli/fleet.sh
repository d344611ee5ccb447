#!/usr/bin/env bash
# The fleet agent against a real broker, as an operator runs it: Debian's mosquitto on 127.0.0.1 at a
# free port, TLS with a test CA made here, a password file; 8 headless players, each with its agent.
# A command to `all` reaches every player; Home Assistant's discovery is retained for each; a
# screenshot arrives as a JPEG; the broker killed and started again: every agent comes back and the
# retained state with it; an agent killed: `offline` by its last will; a wrong CA and a wrong
# password are refused; --remove withdraws a player.
# Usage: fleet.sh PLAYER OUT_DIR
set -u
player=$1 out=$2
dir=$out/fleet
rm -rf "$dir" && mkdir -p "$dir"
players=8
pids=()
broker_pid=
cleanup() {
  for pid in "${pids[@]}" $broker_pid; do kill "$pid" 2>/dev/null; done
  wait 2>/dev/null
}
trap cleanup EXIT
fail() { echo "fleet: $*"; exit 1; }
for tool in mosquitto mosquitto_sub mosquitto_pub mosquitto_passwd openssl; do
  command -v "$tool" >/dev/null || [ -x "/usr/sbin/$tool" ] || fail "$tool is missing (tools/install-deps installs it)"
done
mosquitto_bin=$(command -v mosquitto || echo /usr/sbin/mosquitto)
wait_for() {  # PATTERN SECONDS FILE...
  local pattern=$1 seconds=$2
  shift 2
  for _ in $(seq 1 $((seconds * 10))); do grep -qa -- "$pattern" "$@" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}
count_in() { grep -ca -- "$1" "$2" 2>/dev/null || true; }

# A CA, the broker's certificate for 127.0.0.1 signed by it, and a second CA nobody signed with.
tls=$dir/tls
mkdir -p "$tls"
make_ca() {  # NAME
  openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj "/CN=$1" -keyout "$tls/$1.key" -out "$tls/$1.pem" 2>>"$tls/openssl.log"
}
make_ca fleet-ca && make_ca other-ca || fail "openssl could not make the test CAs: $(cat "$tls/openssl.log")"
printf 'subjectAltName=IP:127.0.0.1\n' >"$tls/san.ext"
openssl req -newkey rsa:2048 -nodes -subj /CN=127.0.0.1 -keyout "$tls/broker.key" -out "$tls/broker.csr" 2>>"$tls/openssl.log" &&
  openssl x509 -req -in "$tls/broker.csr" -CA "$tls/fleet-ca.pem" -CAkey "$tls/fleet-ca.key" -CAcreateserial -days 2 \
    -extfile "$tls/san.ext" -out "$tls/broker.pem" 2>>"$tls/openssl.log" || fail "openssl: $(cat "$tls/openssl.log")"

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
: >"$dir/passwd"
mosquitto_passwd -b "$dir/passwd" operator operator-secret
for i in $(seq 1 $players); do mosquitto_passwd -b "$dir/passwd" "kiosk-$i" "secret-$i"; done
chmod 0600 "$dir/passwd"
cat >"$dir/broker.conf" <<CONF
user $(id -un)
per_listener_settings false
allow_anonymous false
password_file $dir/passwd
persistence false
listener $port 127.0.0.1
cafile $tls/fleet-ca.pem
certfile $tls/broker.pem
keyfile $tls/broker.key
CONF
start_broker() {
  "$mosquitto_bin" -c "$dir/broker.conf" >>"$dir/broker.log" 2>&1 &
  broker_pid=$!
  wait_for "running" 10 "$dir/broker.log" || fail "mosquitto did not start: $(cat "$dir/broker.log")"
}
start_broker
mqtt=(-h 127.0.0.1 -p "$port" --cafile "$tls/fleet-ca.pem" -u operator -P operator-secret)

# The players (2 frames a second: a fleet of 8 sanitized players on 2 cores beside other tests) and their agents.
fleet_config() {  # I CA [EXTRA]
  printf 'broker = "mqtts://127.0.0.1:%s"\nclient_id = "kiosk-%s"\nusername = "kiosk-%s"\npassword_file = "%s"\nca_file = "%s"\nstatus_file = "%s"\ncontrol = "%s"\nstatus_period_s = 1\nkeepalive_s = 5\nreconnect_max_s = 2\n%s' \
    "$port" "$1" "$1" "$dir/p$1/password" "$2" "$dir/p$1/status.json" "$dir/p$1/control" "${3:-}"
}
# Kiosk 1's board has a (mock) check camera, whose view comes with a screenshot.
printf '[board]\nname = "fleet test"\n[camera]\ndevice = "mock"\n' >"$dir/camera-board.toml"
for i in $(seq 1 $players); do
  mkdir -p "$dir/p$i"
  board=()
  [ "$i" = 1 ] && board=(--board "$dir/camera-board.toml")
  echo "secret-$i" >"$dir/p$i/password"
  "$player" play builtin:demo --platform egl --size 64x48 --fps 2 --shader-cache "$dir/shaders" --hal mock "${board[@]}" \
    --control "$dir/p$i/control" --status "$dir/p$i/status.json" >"$dir/p$i/play.log" 2>&1 &
  pids+=($!)
  # The first compiles the shaders into the shared cache; the other seven load them from it.
  [ "$i" = 1 ] && { wait_for "first frame presented" 120 "$dir/p1/play.log" || fail "player 1 did not start: $(cat "$dir/p1/play.log")"; }
  fleet_config "$i" "$tls/fleet-ca.pem" >"$dir/p$i/fleet.toml"
  "$player" fleet --config "$dir/p$i/fleet.toml" >"$dir/p$i/fleet.log" 2>&1 &
  pids+=($!)
  agent_pid[$i]=$!
done
for i in $(seq 1 $players); do
  wait_for "connected to mqtts://127.0.0.1:$port as kiosk-$i" 60 "$dir/p$i/fleet.log" || fail "agent $i did not connect: $(cat "$dir/p$i/fleet.log")"
  wait_for '"state": *"playing"' 120 "$dir/p$i/status.json" || fail "player $i does not play: $(cat "$dir/p$i/play.log")"
done
echo "ok: $players players and agents connected over TLS with passwords"

# Retained for a newcomer: every availability, every state, every discovery entity.
timeout 20 mosquitto_sub "${mqtt[@]}" -t 'ssao-player/+/availability' -v -C $players -W 15 >"$dir/availability.txt" 2>&1
[ "$(grep -c ' online$' "$dir/availability.txt")" = $players ] || fail "retained availability: $(cat "$dir/availability.txt")"
sleep 1.5  # a status period: each state now from a playing player
timeout 20 mosquitto_sub "${mqtt[@]}" -t 'ssao-player/+/state' -v -C $players -W 15 >"$dir/states.txt" 2>&1
[ "$(grep -c '"state":"playing"' "$dir/states.txt")" = $players ] || fail "retained states: $(cat "$dir/states.txt")"
timeout 20 mosquitto_sub "${mqtt[@]}" -t 'homeassistant/#' -v -W 3 >"$dir/discovery.txt" 2>&1
per_player=$(grep -c '^homeassistant/[a-z_]*/ssao_player_kiosk-1/' "$dir/discovery.txt")
[ "$per_player" -ge 10 ] || fail "discovery for kiosk-1: $per_player entities: $(head -3 "$dir/discovery.txt")"
for i in $(seq 1 $players); do
  [ "$(grep -c "^homeassistant/[a-z_]*/ssao_player_kiosk-$i/" "$dir/discovery.txt")" = "$per_player" ] ||
    fail "discovery for kiosk-$i differs from kiosk-1's $per_player entities"
done
# Each entity carries the keys Home Assistant requires.
while read -r topic payload; do
  for key in '"unique_id":' '"availability":\[{"topic":"ssao-player/kiosk-' '"device":{"identifiers":\["ssao-player-kiosk-' '"name":'; do
    grep -q "$key" <<<"$payload" || fail "$topic: no $key in $payload"
  done
  grep -Eq '"(state_topic|command_topic|topic)":"ssao-player/kiosk-' <<<"$payload" || fail "$topic: no topic in $payload"
done < <(grep '^homeassistant/' "$dir/discovery.txt")
[ "$(sed -n 's/.*"unique_id":"\([^"]*\)".*/\1/p' "$dir/discovery.txt" | sort | uniq -d)" = "" ] || fail "a unique_id twice"
echo "ok: discovery retained, $per_player entities per player, each with unique_id, availability, device and topic"

# A command to all: every player pauses and every agent replies; then every one resumes.
to_all() {  # VERB EXPECTED_REPLY
  timeout 40 mosquitto_sub "${mqtt[@]}" -t 'ssao-player/+/reply' -v -C $players -W 30 >"$dir/replies-$1.txt" 2>&1 &
  local sub=$!
  sleep 1
  mosquitto_pub "${mqtt[@]}" -t "ssao-player/all/cmd/$1" -n
  wait $sub
  [ "$(grep -c "\"command\":\"$1\",\"ok\":true,\"reply\":\"$2\"" "$dir/replies-$1.txt")" = $players ] ||
    fail "$1 to all: $(cat "$dir/replies-$1.txt")"
}
to_all pause "ok: paused"
for i in $(seq 1 $players); do
  wait_for '"state": *"paused"' 10 "$dir/p$i/status.json" || fail "player $i did not pause: $(cat "$dir/p$i/status.json")"
done
to_all resume "ok: playing"
# A bad command is refused by the agent and the player stays as it was.
timeout 20 mosquitto_sub "${mqtt[@]}" -t ssao-player/kiosk-2/reply -C 1 -W 10 >"$dir/refused.txt" 2>&1 &
sub=$!
sleep 0.5
mosquitto_pub "${mqtt[@]}" -t ssao-player/kiosk-2/cmd/item -m many
wait $sub
grep -q '"ok":false' "$dir/refused.txt" || fail "item many: $(cat "$dir/refused.txt")"
echo "ok: a command to all reached all $players players; a bad one was refused"

# A self-check, then a screenshot: the frame as a JPEG, retained, and (kiosk 1 has a camera) what
# the camera saw.
mosquitto_pub "${mqtt[@]}" -t ssao-player/kiosk-1/cmd/check -n
wait_for "cmd/check: ok" 30 "$dir/p1/fleet.log" || fail "check: $(tail -3 "$dir/p1/fleet.log")"
wait_for '"passed": *true' 60 "$dir/p1/status.json" || fail "kiosk 1's self-check did not pass: $(cat "$dir/p1/status.json")"
mosquitto_pub "${mqtt[@]}" -t ssao-player/kiosk-1/cmd/screenshot -n
wait_for "cmd/screenshot: ok: frame .* sent as a 64x48 JPEG" 20 "$dir/p1/fleet.log" || fail "screenshot: $(tail -3 "$dir/p1/fleet.log")"
timeout 20 mosquitto_sub "${mqtt[@]}" -t ssao-player/kiosk-1/screenshot/rendered -C 1 -W 10 >"$dir/screenshot.jpg" 2>/dev/null
[ "$(head -c 3 "$dir/screenshot.jpg" | od -An -tx1 | tr -d ' ')" = ffd8ff ] || fail "the screenshot topic holds no JPEG"
grep -q "cmd/screenshot: ok: .*; camera frame sent as a [0-9]*x[0-9]* JPEG" "$dir/p1/fleet.log" || fail "no camera view: $(tail -3 "$dir/p1/fleet.log")"
timeout 20 mosquitto_sub "${mqtt[@]}" -t ssao-player/kiosk-1/screenshot/camera -C 1 -W 10 >"$dir/camera.jpg" 2>/dev/null
[ "$(head -c 3 "$dir/camera.jpg" | od -An -tx1 | tr -d ' ')" = ffd8ff ] || fail "the camera topic holds no JPEG"
echo "ok: a screenshot arrived as a JPEG ($(stat -c %s "$dir/screenshot.jpg") bytes), with the check camera's view ($(stat -c %s "$dir/camera.jpg") bytes)"

# The broker away and back (no persistence: it forgot every retained message): every agent
# reconnects and publishes its retained state again.
kill "$broker_pid"
wait "$broker_pid" 2>/dev/null
sleep 3
start_broker
for i in $(seq 1 $players); do
  wait_for "lost mqtts://127.0.0.1:$port" 1 "$dir/p$i/fleet.log" || fail "agent $i did not notice the broker leave: $(cat "$dir/p$i/fleet.log")"
  for _ in $(seq 1 200); do [ "$(count_in "connected to mqtts" "$dir/p$i/fleet.log")" -ge 2 ] && break; sleep 0.1; done
  [ "$(count_in "connected to mqtts" "$dir/p$i/fleet.log")" -ge 2 ] || fail "agent $i did not reconnect: $(cat "$dir/p$i/fleet.log")"
done
timeout 20 mosquitto_sub "${mqtt[@]}" -t 'ssao-player/+/state' -v -C $players -W 15 >"$dir/states-again.txt" 2>&1
[ "$(grep -c '"state":"playing"' "$dir/states-again.txt")" = $players ] || fail "retained states after the restart: $(cat "$dir/states-again.txt")"
timeout 20 mosquitto_sub "${mqtt[@]}" -t 'ssao-player/+/availability' -v -C $players -W 15 >"$dir/availability-again.txt" 2>&1
[ "$(grep -c ' online$' "$dir/availability-again.txt")" = $players ] || fail "availability after the restart: $(cat "$dir/availability-again.txt")"
echo "ok: the broker restarted; every agent reconnected and its retained state is back"

# An agent killed outright: the broker publishes its last will.
timeout 30 mosquitto_sub "${mqtt[@]}" -t ssao-player/kiosk-3/availability -C 2 -W 20 >"$dir/will.txt" 2>&1 &
sub=$!
sleep 0.5
kill -9 "${agent_pid[3]}"
wait "${agent_pid[3]}" 2>/dev/null
wait $sub
[ "$(tail -1 "$dir/will.txt")" = offline ] || fail "kiosk-3's availability after kill -9: $(cat "$dir/will.txt")"
echo "ok: an agent killed with SIGKILL is offline by its last will"

# Refused: a CA that did not sign the broker, a wrong password. Neither connects.
fleet_config 1 "$tls/other-ca.pem" | sed 's|client_id = "kiosk-1"|client_id = "wrong-ca"|' >"$dir/wrong-ca.toml"
"$player" fleet --config "$dir/wrong-ca.toml" --duration 4 >"$dir/wrong-ca.log" 2>&1
wait_for "certificate verify failed" 1 "$dir/wrong-ca.log" || fail "a wrong CA: $(cat "$dir/wrong-ca.log")"
grep -q "connected to" "$dir/wrong-ca.log" && fail "connected with a wrong CA: $(cat "$dir/wrong-ca.log")"
fleet_config 4 "$tls/fleet-ca.pem" | sed "s|client_id = \"kiosk-4\"|client_id = \"intruder\"|; s|$dir/p4/password|$dir/wrong-password|" >"$dir/wrong-password.toml"
echo wrong >"$dir/wrong-password"
"$player" fleet --config "$dir/wrong-password.toml" --duration 3 >"$dir/wrong-password.log" 2>&1
wait_for "the broker refused the connection: Connection Refused: not authorised" 1 "$dir/wrong-password.log" ||
  fail "a wrong password: $(cat "$dir/wrong-password.log")"
echo "ok: a wrong CA and a wrong password are refused"

# A clean stop says offline; --remove withdraws discovery, state and availability.
kill "${agent_pid[8]}"
wait "${agent_pid[8]}" 2>/dev/null
grep -q "fleet: stopped" "$dir/p8/fleet.log" || fail "agent 8 did not stop cleanly: $(cat "$dir/p8/fleet.log")"
"$player" fleet --config "$dir/p8/fleet.toml" --remove --duration 10 >"$dir/remove.log" 2>&1 || fail "--remove: $(cat "$dir/remove.log")"
timeout 20 mosquitto_sub "${mqtt[@]}" -t 'homeassistant/#' -t 'ssao-player/kiosk-8/#' -v -W 3 >"$dir/after-remove.txt" 2>&1
grep -q "kiosk-8" "$dir/after-remove.txt" && fail "kiosk-8 left retained messages: $(grep kiosk-8 "$dir/after-remove.txt" | head -3)"
grep -q "ssao_player_kiosk-7/" "$dir/after-remove.txt" || fail "--remove took others' discovery too"
echo "fleet: every agent carried commands, state and discovery, and came back after the broker"

#!/bin/bash
# sample.sh PID OUT DIR: VmRSS and VmHWM (MB) every 0.5 s with a wall clock and the rows of DIR/iterations.csv
pid=$1; out=$2; dir=$3
while kill -0 $pid 2>/dev/null; do
  n=$(cat $dir/iterations.csv 2>/dev/null | wc -l)
  awk -v t=$(date +%s.%N) -v n=$n '/VmRSS|VmHWM/{v[$1]=$2} END{printf "%.1f %d %d %d\n", t, v["VmRSS:"]/1024, v["VmHWM:"]/1024, n}' /proc/$pid/status >> $out 2>/dev/null
  sleep 0.5
done

#!/usr/bin/env bash
# The walker demonstration sets of issue 4, rolled out from the committed experts (mean actions).
# Usage: scripts/walker_demos.sh dense|denser|densest|paper|posture|posture_control|context [OUT.h5 [HELD_OUT_ID...]]
#   dense:   experts/walker + walker_dense + walker_context, 20 episodes per passing expert (33 experts, 30 s)
#   denser:  the same + experts/walker_denser, 12 episodes per passing expert (56 experts, 25 s)
#   densest: the same + experts/walker_densest, 8 episodes per passing expert (about as many episodes as
#            denser from more experts)
#   paper:   the densest set's experts, 16 episodes each (77 x 16 = 1232, the paper's scale of about 1200)
#   posture: experts/walker_posture (trained with a posture cost; 17 of 24 pass), 20 episodes each
#   posture_control: experts without the cost, 8 passing ones per speed at -1, 0 and 1 m/s with
#            initial log std -1 from the sets above, 20 episodes each: what the posture set is compared with
#   context: posture_control + the passing {-1, 0, 1} context-conditioned experts (experts/walker_context and
#            walker_context_more), 20 episodes each (the paper's set has 24 context experts of 60)
# OUT.h5 defaults to data/walker/demos_SET.h5; the held-out experts default to the published three (seed 3 at
# -1, 0 and 1 m/s; seed 7 for the posture set).
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: $0 dense|denser|densest|paper|posture|posture_control|context [OUT.h5 [HELD_OUT_ID...]]" >&2; exit 2; }
set_name=$1
# The order of the directories fixes each episode's seed, so new ones go before walker_context.
dirs="experts/walker experts/walker_dense"
last=experts/walker_context
only=""
case $set_name in
  dense) more=""; episodes=20 ;;
  denser) more="experts/walker_denser"; episodes=12 ;;
  densest) more="experts/walker_denser experts/walker_densest"; episodes=8 ;;
  paper) more="experts/walker_denser experts/walker_densest"; episodes=16 ;;
  posture) dirs=""; more=""; last=experts/walker_posture; episodes=20 ;;
  posture_control|context) more="experts/walker_denser experts/walker_densest"; last=""; episodes=20
    only="$(printf 'speed-1_logstd-1_seed%s ' 1 2 3 5 6 7 8 9)$(printf 'speed0_logstd-1_seed%s ' 0 2 3 8 9 10 12 15)"
    only+="$(printf 'speed1_logstd-1_seed%s ' 0 1 2 3 4 5 6 7)"
    if [ "$set_name" = context ]; then  # after the control's experts, whose episodes then stay the same
      last="experts/walker_context experts/walker_context_more"
      only+="ctx-1_0_1_logstd0_seed0 $(printf 'ctx-1_0_1_logstd-1_seed%s ' 1 2 3 4 5 6 7 8)"
    fi ;;
  *) echo "$0: unknown set '$set_name' (dense, denser, densest, paper, posture, posture_control or context)" >&2; exit 2 ;;
esac
dirs="$dirs $more $last"
out=${2:-data/walker/demos_$set_name.h5}
shift $(( $# >= 2 ? 2 : 1 ))
default_seed=3
[ "$set_name" = posture ] && default_seed=7  # seed 3 fails the bar at every speed there
held_out=${*:-speed-1_logstd-1_seed$default_seed speed0_logstd-1_seed$default_seed speed1_logstd-1_seed$default_seed}
passing=$(for d in $dirs; do printf '%s/eval.json ' "$d"; done)
# shellcheck disable=SC2086  # lists of directories and ids split on purpose
build/vaegail demos collect --experts-dir $dirs --passing $passing --out "$out" \
    --episodes-per-expert $episodes --held-out $held_out ${only:+--only $only}

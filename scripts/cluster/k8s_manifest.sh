#!/usr/bin/env bash
# Writes the Kubernetes manifest of a cluster sweep's run (scripts/cluster/submit.sh --k8s calls
# it; docs/bench.md, "On a cluster"): --job array, an Indexed Job (completionMode: Indexed) of
# --tasks completions running scripts/cluster/task.sh, JOB_COMPLETION_INDEX choosing the line of
# the run's tasks.txt; --job merge, a Job running scripts/cluster/merge.sh, to apply once the
# array has ended (Kubernetes has no job dependencies: docs/bench.md gives the kubectl wait).
#
#   bash scripts/cluster/k8s_manifest.sh --job array|merge --run NAME --pack packs/NAME --tasks N --image IMG --pvc CLAIM
#       [--mount PATH] [--parallelism P] [--constraint GPU_PRODUCT]
#
# The shared folder is the PersistentVolumeClaim CLAIM mounted at PATH (default /causticlab) in
# every pod; node-local storage is an emptyDir at /scratch (TMPDIR). An array pod asks for one
# GPU (nvidia.com/gpu, from NVIDIA's device plugin) and sets NVIDIA_DRIVER_CAPABILITIES to
# graphics,compute,utility: without `graphics` the NVIDIA container toolkit mounts no Vulkan ICD
# (nvidia_icd.json) and the driver's Vulkan library, and causticlab finds no device. A pod that
# fails is retried once (backoffLimitPerIndex: 1, Kubernetes 1.29 and later), its replacement
# started only once it has ended (podReplacementPolicy: Failed); task.sh itself runs a
# failed bench once more. --constraint selects nodes by the GPU feature discovery label
# nvidia.com/gpu.product (one array per GPU model, as Slurm's --constraint).
set -euo pipefail

job="" run="" pack_rel="" tasks="" image="" pvc="" mount=/causticlab parallelism="" constraint=""
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || { echo "k8s_manifest: $1 needs a value" >&2; exit 2; }
    case "$1" in
        --job) job=$2 ;;
        --run) run=$2 ;;
        --pack) pack_rel=$2 ;;
        --tasks) tasks=$2 ;;
        --image) image=$2 ;;
        --pvc) pvc=$2 ;;
        --mount) mount=$2 ;;
        --parallelism) parallelism=$2 ;;
        --constraint) constraint=$2 ;;
        *) echo "k8s_manifest: unknown option '$1'" >&2; exit 2 ;;
    esac
    shift 2
done
case "$job" in array|merge) ;; *) echo "k8s_manifest: --job array or --job merge" >&2; exit 2 ;; esac
[ -n "$run" ] && [ -n "$pack_rel" ] && [ -n "$image" ] && [ -n "$pvc" ] || { echo "k8s_manifest: --run, --pack, --image and --pvc are required" >&2; exit 2; }
[[ "$tasks" =~ ^[1-9][0-9]*$ ]] || { echo "k8s_manifest: --tasks: '$tasks' is not a whole number above 0" >&2; exit 2; }
[ -z "$parallelism" ] || [[ "$parallelism" =~ ^[1-9][0-9]*$ ]] || { echo "k8s_manifest: --parallelism: '$parallelism' is not a whole number above 0" >&2; exit 2; }
# A Job's name is a DNS label (63 characters at most: lowercase letters, digits, '-').
name=causticlab-$(tr 'A-Z._' 'a-z--' <<<"$run" | tr -cd 'a-z0-9-')
[ "$job" = merge ] && name=$name-merge
[ "${#name}" -le 63 ] || { echo "k8s_manifest: the Job name $name is over 63 characters: give a shorter --name" >&2; exit 2; }
# The run's name is also a label value: letters, digits, '.', '_', '-', starting and ending with
# a letter or digit, 63 characters at most.
[[ "$run" =~ ^[A-Za-z0-9]([A-Za-z0-9._-]{0,61}[A-Za-z0-9])?$ ]] || { echo "k8s_manifest: --run '$run' is not a label value (letters, digits, '.', '_', '-'; 63 at most)" >&2; exit 2; }
q() { printf '"%s"' "$(sed 's/["\\]/\\&/g' <<<"$1")"; }   # a YAML double-quoted string

cat <<YAML
# causticlab cluster sweep, run $run: $( [ "$job" = array ] && echo "the array ($tasks indexed tasks)" || echo "the merge, to apply once the array has ended" )
apiVersion: batch/v1
kind: Job
metadata:
  name: $name
  labels:
    app.kubernetes.io/name: causticlab
    causticlab/run: $(q "$run")
spec:
YAML
if [ "$job" = array ]; then
    cat <<YAML
  completionMode: Indexed
  completions: $tasks
  parallelism: ${parallelism:-$tasks}
  backoffLimitPerIndex: 1
  podReplacementPolicy: Failed
YAML
else
    echo "  backoffLimit: 0"
fi
cat <<YAML
  template:
    metadata:
      labels:
        app.kubernetes.io/name: causticlab
    spec:
      restartPolicy: Never
YAML
if [ "$job" = array ] && [ -n "$constraint" ]; then
    echo "      nodeSelector:"
    echo "        nvidia.com/gpu.product: $(q "$constraint")"
fi
cat <<YAML
      containers:
        - name: $job
          image: $(q "$image")
          command: ["bash", $(q "$mount/$pack_rel/$( [ "$job" = array ] && echo task.sh || echo merge.sh )")]
          env:
            - name: CAUSTICLAB_SHARED
              value: $(q "$mount")
            - name: CAUSTICLAB_RUN
              value: $(q "$run")
            - name: TMPDIR
              value: /scratch
YAML
if [ "$job" = array ]; then
    cat <<YAML
            - name: NVIDIA_DRIVER_CAPABILITIES
              value: graphics,compute,utility
          resources:
            limits:
              nvidia.com/gpu: 1
YAML
fi
cat <<YAML
          volumeMounts:
            - name: shared
              mountPath: $(q "$mount")
            - name: scratch
              mountPath: /scratch
      volumes:
        - name: shared
          persistentVolumeClaim:
            claimName: $(q "$pvc")
        - name: scratch
          emptyDir: {}
YAML

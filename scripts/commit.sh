# Sourced by the scripts that name a commit (gpu_pack.sh, photon_rate.sh, soak.sh), from the
# repository's root.
#
# code_commit prints the commit the measured code is, as `bench::meta::commit` computes it:
# HEAD's short hash, with `-dirty` when tracked files other than results/ and Markdown differ
# (results being rewritten by the run, or notes edited beside it, do not make the code dirty).
# It fails, printing nothing, outside a git work tree.
code_commit() {
    local c
    c=$(git rev-parse --short HEAD) || return 1
    if [ -n "$(git status --porcelain --untracked-files=no -- . ':(exclude)results' ':(exclude,glob)**/*.md')" ]; then
        c="$c-dirty"
    fi
    echo "$c"
}

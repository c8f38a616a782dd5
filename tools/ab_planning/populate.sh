# Sourced by tools/ab_planning.sh and tools/ab_plans.sh (from the repository root): writes the
# revisions both link into one binary (tools/ab_planning/).

# Writes revision $1 (`.`: the working tree) to directory $2 as a package named $3. The files get
# the time of writing (`tar -m`): cargo rebuilds a path dependency only when a file is newer than
# its last build, so a copy with the commit's older times would reuse the build of another.
populate() {
  rm -rf "$2"
  mkdir -p "$2"
  if [ "$1" = . ]; then
    git ls-files -co --exclude-standard -z | tar --null -T - -c | tar -x -m -C "$2"
  else
    git archive "$1" | tar -x -m -C "$2"
  fi
  sed -i "0,/^name = \"profilegen\"\$/s//name = \"$3\"/" "$2/Cargo.toml"
}

"""The machinery every study uses: trials run on an executor (local processes or Ray), records
written as they arrive and resumed, fingerprints that keep stale records out, one writer per
folder, workers that end with their command, and the statistics of success rates.

* `runner`: specs to records, through an executor, into a results file (resumable);
* `executors`: local worker processes and Ray tasks, the same records either way;
* `results`: the checksummed CSV a record is whole or absent in;
* `fingerprint`: what decides a record (scenario, object content, protocol, version);
* `lock`: one writer per output folder; `reaper`: workers follow their parent's death;
* `stats`: Wilson intervals and rates.
"""

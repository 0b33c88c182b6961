from enum import StrEnum

class SolverStart(StrEnum):
    BRANCH = "branch"
    MULTI_START = "multi_start"
    SEED = "seed"

    def __str__(self) -> str:
        return str(self.value)

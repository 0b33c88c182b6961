from enum import StrEnum

class PoseSet(StrEnum):
    CAL = "cal"
    VAL = "val"

    def __str__(self) -> str:
        return str(self.value)

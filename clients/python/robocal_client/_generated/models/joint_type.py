from enum import StrEnum

class JointType(StrEnum):
    REVOLUTE = "revolute"

    def __str__(self) -> str:
        return str(self.value)
